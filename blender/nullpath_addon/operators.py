"""Add → nullpath → Black hole / Wormhole: an Empty carrying the hole's parameters."""

import bpy
from bpy.props import FloatProperty, FloatVectorProperty

from . import spacetime


class _AddHole:
    bl_options = {"REGISTER", "UNDO"}

    location: FloatVectorProperty(
        name="Location", description="Where the hole is (default: the 3D cursor)", subtype="TRANSLATION", size=3,
    )

    kind = None
    default_name = None

    def set_parameters(self, hole):
        raise NotImplementedError

    def execute(self, context):
        obj = bpy.data.objects.new(self.default_name, None)
        obj.location = self.location if self.properties.is_property_set("location") else context.scene.cursor.location
        context.collection.objects.link(obj)
        obj.nullpath.kind = self.kind
        self.set_parameters(obj.nullpath)
        # The engine exports the scene with Blender's operators from the render thread: keep the
        # interface from changing the scene meanwhile.
        context.scene.render.use_lock_interface = True
        for other in context.selected_objects:
            other.select_set(False)
        obj.select_set(True)
        context.view_layer.objects.active = obj
        return {"FINISHED"}


class NULLPATH_OT_add_black_hole(_AddHole, bpy.types.Operator):
    """Add a black hole: nullpath curves light about it (its sphere shows the horizon)"""

    bl_idname = "nullpath.add_black_hole"
    bl_label = "Black hole"
    kind = spacetime.BLACK_HOLE
    default_name = "Black hole"

    mass: FloatProperty(name="Mass", default=1.0, min=0.0, soft_max=10.0)
    spin: FloatProperty(name="Spin", default=0.0, soft_min=-10.0, soft_max=10.0)
    charge: FloatProperty(name="Charge", default=0.0, soft_min=-10.0, soft_max=10.0)

    def set_parameters(self, hole):
        hole.mass, hole.spin, hole.charge = self.mass, self.spin, self.charge


class NULLPATH_OT_add_wormhole(_AddHole, bpy.types.Operator):
    """Add a wormhole: a throat to another sky (its sphere shows the throat)"""

    bl_idname = "nullpath.add_wormhole"
    bl_label = "Wormhole"
    kind = spacetime.WORMHOLE
    default_name = "Wormhole"

    throat: FloatProperty(name="Throat", default=1.0, min=1e-6, soft_max=10.0)

    def set_parameters(self, hole):
        hole.throat = self.throat


class VIEW3D_MT_nullpath_add(bpy.types.Menu):
    bl_idname = "VIEW3D_MT_nullpath_add"
    bl_label = "nullpath"

    def draw(self, _context):
        self.layout.operator(NULLPATH_OT_add_black_hole.bl_idname, icon="SHADING_SOLID")
        self.layout.operator(NULLPATH_OT_add_wormhole.bl_idname, icon="SHADING_WIRE")


def _add_menu(self, _context):
    self.layout.menu(VIEW3D_MT_nullpath_add.bl_idname, icon="LIGHT_SUN")


_classes = (NULLPATH_OT_add_black_hole, NULLPATH_OT_add_wormhole, VIEW3D_MT_nullpath_add)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.VIEW3D_MT_add.append(_add_menu)


def unregister():
    bpy.types.VIEW3D_MT_add.remove(_add_menu)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
