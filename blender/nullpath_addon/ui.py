"""Panels: a hole's parameters in the Object properties, the render settings in the Render
properties, and Blender's own camera, light, material and world panels for the nullpath engine."""

import bpy

from . import spacetime
from .engine import NullpathRenderEngine
from .properties import hole_radius

ENGINE = NullpathRenderEngine.bl_idname


class OBJECT_PT_nullpath_hole(bpy.types.Panel):
    bl_label = "nullpath"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "object"

    @classmethod
    def poll(cls, context):
        return context.object is not None and context.object.type == "EMPTY"

    def draw(self, context):
        obj = context.object
        hole = obj.nullpath
        layout = self.layout
        layout.use_property_split = True
        layout.prop(hole, "kind")
        if hole.kind == spacetime.BLACK_HOLE:
            for name in ("mass", "spin", "charge"):
                layout.prop(hole, name)
            problem = spacetime.check_black_hole("", hole.mass, hole.spin, hole.charge)
            if problem:
                layout.label(text=problem.lstrip(": "), icon="ERROR")
            else:
                layout.label(text=f"Horizon radius {hole_radius(hole):.4g}")
            layout.prop(hole, "accretion_disk")
            if hole.accretion_disk:
                for name in ("disk_outer_radius", "disk_temperature", "disk_luminance"):
                    layout.prop(hole, name)
        elif hole.kind == spacetime.WORMHOLE:
            layout.prop(hole, "wormhole_shape")
            layout.prop(hole, "throat")
            if hole.wormhole_shape == spacetime.INTERSTELLAR:
                layout.prop(hole, "length")
                layout.prop(hole, "lensing_width")
            layout.prop(hole, "far_side")
        if hole.kind != "NONE" and tuple(obj.scale) != (1.0, 1.0, 1.0):
            layout.label(text="The hole's size is its parameters': its scale is ignored", icon="INFO")


class RENDER_PT_nullpath(bpy.types.Panel):
    bl_label = "nullpath"
    bl_space_type = "PROPERTIES"
    bl_region_type = "WINDOW"
    bl_context = "render"
    COMPAT_ENGINES = {ENGINE}

    @classmethod
    def poll(cls, context):
        return context.engine in cls.COMPAT_ENGINES

    def draw(self, context):
        settings = context.scene.nullpath
        layout = self.layout
        layout.use_property_split = True
        for name in ("samples", "max_depth", "seed", "export_dir"):
            layout.prop(settings, name)
        layout.prop(context.scene.render, "use_lock_interface")


# EEVEE's node-based surface panels, the place to edit a material's or the world's shader.
SURFACE_PANELS = ("EEVEE_MATERIAL_PT_surface", "EEVEE_WORLD_PT_surface", "DATA_PT_EEVEE_light")


def blender_panels():
    """Blender's panels to show with nullpath (camera, lights, materials, world, output): those its
    external-engine template lists, the ones marked for 'BLENDER_RENDER', and the surface panels."""
    for panel in bpy.types.Panel.__subclasses__():
        compatible = getattr(panel, "COMPAT_ENGINES", ())
        if "BLENDER_RENDER" in compatible or (panel.__name__ in SURFACE_PANELS and isinstance(compatible, set)):
            yield panel


_classes = (OBJECT_PT_nullpath_hole, RENDER_PT_nullpath)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    for panel in blender_panels():
        panel.COMPAT_ENGINES.add(ENGINE)


def unregister():
    for panel in blender_panels():
        panel.COMPAT_ENGINES.discard(ENGINE)
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
