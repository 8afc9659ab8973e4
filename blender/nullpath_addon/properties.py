"""The add-on's settings: a hole's parameters (on its Empty), the render's (on the scene), and
where the `nullpath` program is (the add-on's preferences)."""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, FloatVectorProperty, IntProperty, PointerProperty
from bpy.props import StringProperty

from . import spacetime

ADDON_NAME = __package__


def hole_radius(hole):
    """What the Empty's sphere shows: the outer horizon of a black hole, the throat of a wormhole."""
    if hole.kind == spacetime.WORMHOLE:
        return hole.throat
    return spacetime.horizon_radius(hole.mass, hole.spin, hole.charge)


def _show_size(hole, _context):
    """Keeps the Empty's display size at the horizon or throat as the parameters change."""
    obj = hole.id_data
    if hole.kind != "NONE" and obj.type == "EMPTY":
        obj.empty_display_type = "SPHERE"
        # Blender refuses a display size of 0 (a hole of mass 0): show a dot.
        obj.empty_display_size = max(hole_radius(hole), 1e-4)


class NullpathHole(bpy.types.PropertyGroup):
    """A black hole or wormhole: the spacetime nullpath puts where the Empty is."""

    kind: EnumProperty(
        name="Kind",
        items=(
            ("NONE", "None", "An ordinary Empty"),
            (spacetime.BLACK_HOLE, "Black hole", "Schwarzschild, Kerr, Reissner–Nordström or Kerr–Newman"),
            (spacetime.WORMHOLE, "Wormhole", "A traversable wormhole with two sides"),
        ),
        default="NONE",
        update=_show_size,
    )
    mass: FloatProperty(
        name="Mass", description="The hole's mass M in scene units (G = c = 1): the horizon's radius is 2M without spin or charge",
        default=1.0, min=0.0, soft_max=10.0, precision=4, update=_show_size,
    )
    spin: FloatProperty(
        name="Spin", description="Angular momentum per unit mass a = J/M (|a| ≤ M), counter-clockwise about the Empty's local Z",
        default=0.0, soft_min=-10.0, soft_max=10.0, precision=4, update=_show_size,
    )
    charge: FloatProperty(
        name="Charge", description="Electric charge Q (G = c = 4πε₀ = 1); spin² + charge² ≤ mass²",
        default=0.0, soft_min=-10.0, soft_max=10.0, precision=4, update=_show_size,
    )
    wormhole_shape: EnumProperty(
        name="Shape",
        items=(
            (spacetime.ELLIS, "Ellis", "Ellis's wormhole: a throat and nothing else"),
            (spacetime.INTERSTELLAR, "Interstellar", "The wormhole of Interstellar (James et al. 2015): a throat, a length and a lensing width"),
        ),
        default=spacetime.ELLIS,
    )
    throat: FloatProperty(
        name="Throat", description="Throat radius b₀ in scene units", default=1.0, min=1e-6, soft_max=10.0,
        precision=4, update=_show_size,
    )
    length: FloatProperty(
        name="Length", description="Length 2a of the cylindrical interior (Interstellar)", default=0.01,
        min=0.0, soft_max=10.0, precision=4,
    )
    lensing_width: FloatProperty(
        name="Lensing width", description="Width 𝒲 of the strongly lensed ring about the mouths (Interstellar)",
        default=0.05, min=1e-9, soft_max=10.0, precision=4,
    )
    far_side: FloatVectorProperty(
        name="Far side", description="The sky seen through the wormhole (a constant radiance)", subtype="COLOR",
        size=3, min=0.0, soft_max=1.0, default=(0.0, 0.0, 0.0),
    )
    accretion_disk: BoolProperty(
        name="Accretion disk", description="A thin disk of hot gas in the hole's equatorial plane (Novikov–Thorne)",
        default=False,
    )
    disk_outer_radius: FloatProperty(
        name="Outer radius", description="The disk's outer edge (Boyer–Lindquist r, scene units); beyond the innermost stable orbit",
        default=20.0, min=0.0, soft_max=100.0,
    )
    disk_temperature: FloatProperty(
        name="Temperature", description="The hottest ring's temperature, kelvin", default=10000.0, min=100.0,
        soft_max=50000.0,
    )
    disk_luminance: FloatProperty(
        name="Luminance", description="The hottest ring's luminance at rest", default=1.0, min=0.0, soft_max=100.0,
    )


class NullpathRender(bpy.types.PropertyGroup):
    """The scene's render settings for nullpath (the image size is Blender's)."""

    samples: IntProperty(name="Samples", description="Samples per pixel", default=64, min=1, soft_max=4096)
    max_depth: IntProperty(name="Max bounces", description="Longest path, in surface interactions", default=8, min=0, max=1024)
    seed: IntProperty(name="Seed", description="Random seed: the image depends only on it", default=0, min=0)
    export_dir: StringProperty(
        name="Keep export in",
        description="Folder to write the exported scene (scene.toml, scene.glb, the sky) and image to, and keep; empty: a temporary folder, removed after the render",
        subtype="DIR_PATH", default="",
    )


class NullpathPreferences(bpy.types.AddonPreferences):
    bl_idname = ADDON_NAME

    binary: StringProperty(
        name="nullpath program",
        description="Path of the nullpath executable; empty: $NULLPATH_BIN, else nullpath on PATH",
        subtype="FILE_PATH", default="",
    )

    def draw(self, _context):
        self.layout.prop(self, "binary")


_classes = (NullpathHole, NullpathRender, NullpathPreferences)


def register():
    for cls in _classes:
        bpy.utils.register_class(cls)
    bpy.types.Object.nullpath = PointerProperty(type=NullpathHole)
    bpy.types.Scene.nullpath = PointerProperty(type=NullpathRender)


def unregister():
    del bpy.types.Scene.nullpath
    del bpy.types.Object.nullpath
    for cls in reversed(_classes):
        bpy.utils.unregister_class(cls)
