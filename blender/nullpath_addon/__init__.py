"""nullpath for Blender: black holes and wormholes as Empties, and a render engine that hands the
scene to the `nullpath` renderer (docs/blender.md in nullpath's sources).

The add-on keeps Blender's side thin: the scene is exported to glTF (Blender's own exporter) and a
nullpath scene file, `nullpath render` renders it, and the image comes back into the render result.
"""

bl_info = {
    "name": "nullpath",
    "author": "nullpath contributors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "Add > nullpath; Render Properties > Render Engine > nullpath",
    "description": "Black holes and wormholes rendered by nullpath, a renderer for curved spacetime",
    "category": "Render",
}

import addon_utils  # noqa: E402

from . import engine, export, operators, properties, ui  # noqa: E402

_modules = (properties, operators, engine, ui)


def register():
    # The export runs Blender's glTF exporter, an add-on of its own that a build or a person may
    # have left off (it is on in Blender's factory settings).
    if not addon_utils.check(export.GLTF_ADDON)[1]:
        addon_utils.enable(export.GLTF_ADDON, default_set=True)
    for module in _modules:
        module.register()


def unregister():
    for module in reversed(_modules):
        module.unregister()
