"""Blender's scene as a nullpath scene: a glTF file of the geometry, materials and lights (Blender's
exporter) and a scene file (camera, sky, spacetime, render settings) beside it.

nullpath's world is y-up and its hole sits at the origin; Blender's is z-up with the hole anywhere.
Every position and direction goes through one map: Blender's (x, y, z) is nullpath's (x, z, −y) (the
glTF exporter's own y-up conversion, so the geometry and the scene file agree), and the whole world
is then moved so that the hole's place is the origin.
"""

import json
import math
import os
import shutil
import struct
import tempfile

import bpy
from mathutils import Vector

from . import spacetime, toml_writer

SCENE_FILE = "scene.toml"
# Blender's glTF exporter, an add-on that ships with Blender.
GLTF_ADDON = "io_scene_gltf2"
GLTF_FILE = "scene.glb"
# Panorama formats nullpath reads (docs/scene-format.md, `type = "equirect"`).
SKY_FORMATS = (".png", ".exr", ".hdr")
# Turns a nullpath equirect sky so that it lies as Blender's does: Blender puts the panorama's
# centre at +X with −Y to its right; nullpath at −z with +x to its right. Blender's +X is nullpath's
# +x, reached from −z by a quarter turn clockwise seen from above.
BLENDER_EQUIRECT_ROTATION_DEG = -90.0


class ExportError(Exception):
    """What keeps the scene from being exported, worded for the person rendering."""


def to_nullpath(v):
    """Blender's z-up (x, y, z) in nullpath's y-up world: (x, z, −y)."""
    return Vector((v[0], v[2], -v[1]))


def numbers(v):
    return [float(x) for x in v]


def holes_of(scene):
    """The Empties that are holes and render."""
    return [o for o in scene.objects if o.type == "EMPTY" and o.nullpath.kind != "NONE" and not o.hide_render]


def the_hole(scene):
    """The one hole of the scene, or None: nullpath renders one spacetime at a time."""
    holes = holes_of(scene)
    if len(holes) > 1:
        names = ", ".join(sorted(o.name for o in holes))
        raise ExportError(f"nullpath renders one black hole or wormhole at a time; this scene has {len(holes)}: {names}")
    return holes[0] if holes else None


def spacetime_table(hole_object, matrix):
    """`[spacetime]` of the hole, its spin axis the Empty's local Z."""
    hole = hole_object.nullpath
    name = hole_object.name
    if hole.kind == spacetime.WORMHOLE:
        problem = spacetime.check_wormhole(name, hole.wormhole_shape, hole.throat, hole.length, hole.lensing_width)
        if problem:
            raise ExportError(problem)
        return spacetime.wormhole_table(hole.wormhole_shape, hole.throat, hole.length, hole.lensing_width)
    problem = spacetime.check_black_hole(name, hole.mass, hole.spin, hole.charge)
    if problem:
        raise ExportError(problem)
    axis = to_nullpath(matrix.to_3x3() @ Vector((0.0, 0.0, 1.0)))
    if axis.length == 0.0:
        raise ExportError(f"{name}: its scale is 0 along its Z axis, so it has no spin axis")
    return spacetime.black_hole_table(hole.mass, hole.spin, hole.charge, numbers(axis.normalized()))


def accretion_disk_table(hole_object, axis):
    """`[accretion_disk]`, or None. A spinning hole's disk lies in its equatorial plane, which
    nullpath takes from the spacetime's axis; a non-spinning one's is given as `normal`."""
    hole = hole_object.nullpath
    if hole.kind != spacetime.BLACK_HOLE or not hole.accretion_disk:
        return None
    if hole.mass <= 0.0:
        raise ExportError(f"{hole_object.name}: an accretion disk needs a hole of mass > 0")
    table = {
        "outer_radius": hole.disk_outer_radius,
        "temperature": hole.disk_temperature,
        "luminance": hole.disk_luminance,
    }
    if hole.spin == 0.0:
        table["normal"] = axis
    return table


def vertical_fov(camera, width, height, pixel_aspect):
    """The camera's vertical field of view in degrees, as Blender frames the image: the sensor's
    fitted side (`sensor_fit`; AUTO fits the longer side with the sensor width) spans
    2·atan(sensor / 2·lens)."""
    size_x, size_y = width * pixel_aspect[0], height * pixel_aspect[1]
    fit = camera.sensor_fit
    if fit == "AUTO":
        fit = "HORIZONTAL" if size_x >= size_y else "VERTICAL"
        sensor = camera.sensor_width
    else:
        sensor = camera.sensor_width if fit == "HORIZONTAL" else camera.sensor_height
    half = math.atan(sensor / (2.0 * camera.lens))
    if fit == "HORIZONTAL":
        half = math.atan(math.tan(half) * size_y / size_x)
    return math.degrees(2.0 * half)


def camera_table(scene, camera_object, matrix, origin, width, height):
    """`[camera]`: position, look_at one unit ahead, up, fov, and depth of field."""
    camera = camera_object.data
    if camera.type != "PERSP":
        raise ExportError(f"camera {camera_object.name}: nullpath renders perspective cameras only, not {camera.type.lower()}")
    if camera.shift_x != 0.0 or camera.shift_y != 0.0:
        raise ExportError(f"camera {camera_object.name}: lens shift is not supported by nullpath; set Shift X and Y to 0")
    rotation = matrix.to_3x3().normalized()
    position = to_nullpath(matrix.translation) - origin
    forward = to_nullpath(rotation @ Vector((0.0, 0.0, -1.0))).normalized()
    up = to_nullpath(rotation @ Vector((0.0, 1.0, 0.0))).normalized()
    render = scene.render
    table = {
        "position": numbers(position),
        "look_at": numbers(position + forward),
        "up": numbers(up),
        "fov": vertical_fov(camera, width, height, (render.pixel_aspect_x, render.pixel_aspect_y)),
    }
    dof = camera.dof
    if dof.use_dof:
        # Cycles' thin lens: aperture radius = focal length / (2 · f-number), in metres.
        table["aperture"] = camera.lens * 1e-3 / (2.0 * dof.aperture_fstop)
        distance = dof.focus_distance
        if dof.focus_object is not None:
            to_focus = dof.focus_object.matrix_world.translation - matrix.translation
            distance = abs(to_focus.dot(rotation @ Vector((0.0, 0.0, -1.0))))
        if distance > 0.0:
            table["focus_distance"] = distance
    return table


def uses_nodes(world):
    """Whether the world's shader is its node tree: always in Blender 5.0 and later (which
    deprecate `World.use_nodes`), else where the world's Use Nodes is on."""
    return world.node_tree is not None and (bpy.app.version >= (5, 0, 0) or world.use_nodes)


def background_node(world):
    """The Background shader that feeds the world's active output, or None."""
    if not uses_nodes(world):
        return None
    for node in world.node_tree.nodes:
        if node.type == "OUTPUT_WORLD" and node.is_active_output:
            links = node.inputs["Surface"].links
            if links and links[0].from_node.type == "BACKGROUND":
                return links[0].from_node
    return None


def sky_table(world, directory, warnings):
    """`[sky]` from Blender's world: an environment texture as the panorama (copied into
    `directory`), else its colour times strength as a constant radiance."""
    if world is None:
        return {"type": "constant", "radiance": [0.0, 0.0, 0.0]}
    node = background_node(world)
    if node is None:
        if uses_nodes(world):
            warnings.append(f"world {world.name}: no Background shader feeds its output; the sky is its viewport colour")
        return {"type": "constant", "radiance": numbers(world.color)}
    strength_input = node.inputs["Strength"]
    if strength_input.is_linked:
        warnings.append(f"world {world.name}: its strength is linked; nullpath takes the unlinked value")
    strength = float(strength_input.default_value)
    colour = node.inputs["Color"]
    if not colour.is_linked:
        return {"type": "constant", "radiance": [strength * float(c) for c in colour.default_value[:3]]}
    texture = colour.links[0].from_node
    if texture.type != "TEX_ENVIRONMENT" or texture.image is None:
        warnings.append(f"world {world.name}: its colour comes from a {texture.bl_label} node; nullpath takes the unlinked colour")
        return {"type": "constant", "radiance": [strength * float(c) for c in colour.default_value[:3]]}
    if texture.projection != "EQUIRECTANGULAR":
        raise ExportError(f"world {world.name}: nullpath reads equirectangular panoramas only, not {texture.projection.lower()}")
    if texture.inputs["Vector"].is_linked:
        warnings.append(f"world {world.name}: the environment texture's mapping is ignored")
    return {
        "type": "equirect",
        "file": copy_panorama(texture.image, directory),
        "intensity": strength,
        "rotation_deg": BLENDER_EQUIRECT_ROTATION_DEG,
    }


def copy_panorama(image, directory):
    """Copies the environment image next to the scene file (a scene reads files in its own folder
    only); its name there."""
    source = bpy.path.abspath(image.filepath, library=image.library)
    extension = os.path.splitext(source)[1].lower()
    if extension not in SKY_FORMATS:
        raise ExportError(f"image {image.name}: nullpath reads PNG, OpenEXR and Radiance HDR panoramas, not '{extension or source}'")
    name = "sky" + extension
    if image.packed_file is not None:
        write_atomically(os.path.join(directory, name), image.packed_file.data)
    elif os.path.isfile(source):
        copy_atomically(source, os.path.join(directory, name))
    else:
        raise ExportError(f"image {image.name}: cannot find its file '{source}'")
    return name


def write_atomically(path, data):
    """Writes `data` (bytes) to a temporary file beside `path`, then renames it into place."""
    descriptor, temporary = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".partial-")
    try:
        with os.fdopen(descriptor, "wb") as file:
            file.write(data)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def copy_atomically(source, path):
    descriptor, temporary = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".partial-")
    os.close(descriptor)
    try:
        shutil.copyfile(source, temporary)
        os.replace(temporary, path)
    except BaseException:
        os.unlink(temporary)
        raise


def export_gltf(path):
    """The scene's renderable objects and lights, as they are at the current frame, into a binary
    glTF at `path`, y-up, modifiers applied, cameras left out (the scene file has the camera), lights in unitless intensity
    (W / 4π: the radiance scale Cycles gives a point light)."""
    try:
        options = bpy.ops.export_scene.gltf.get_rna_type().properties.keys()
    except KeyError:
        raise ExportError("Blender's glTF exporter is off: enable the add-on 'Import-Export: glTF 2.0 format' in Preferences") from None
    # The option was renamed in Blender 3.6.
    lighting = "export_import_convert_lighting_mode" if "export_import_convert_lighting_mode" in options else "convert_lighting_mode"
    directory = tempfile.mkdtemp(dir=os.path.dirname(path), prefix=".partial-")
    try:
        written = os.path.join(directory, os.path.basename(path))
        result = bpy.ops.export_scene.gltf(
            filepath=written,
            export_format="GLB",
            use_renderable=True,
            export_cameras=False,
            export_lights=True,
            export_yup=True,
            export_apply=True,
            export_animations=False,
            # Else the exporter evaluates the scene at frame 0.
            export_current_frame=True,
            **{lighting: "COMPAT"},
        )
        if result != {"FINISHED"} or not os.path.isfile(written):
            raise ExportError("Blender's glTF exporter did not write the scene")
        os.replace(written, path)
    finally:
        shutil.rmtree(directory, ignore_errors=True)


def places_anything(glb):
    """Whether the binary glTF file has any node: with nothing to render the exporter writes a
    document without nodes, which nullpath refuses."""
    with open(glb, "rb") as file:
        header = file.read(20)  # magic, version, length; the JSON chunk's length and type
        length, kind = struct.unpack("<II", header[12:20])
        if header[:4] != b"glTF" or kind != 0x4E4F534A:  # "JSON"
            raise ExportError("Blender's glTF exporter wrote a file that is not binary glTF")
        return bool(json.loads(file.read(length)).get("nodes"))


def resolution(scene):
    """The image size Blender would render, percentage applied."""
    render = scene.render
    scale = render.resolution_percentage / 100.0
    return max(1, int(render.resolution_x * scale)), max(1, int(render.resolution_y * scale))


def scene_tables(scene, depsgraph, directory, warnings):
    """The scene file's tables; writes the sky's panorama into `directory`."""
    if scene.camera is None:
        raise ExportError("the scene has no camera")
    width, height = resolution(scene)
    hole = the_hole(scene)
    evaluated = lambda obj: obj.evaluated_get(depsgraph).matrix_world  # noqa: E731
    tables = {}
    origin = Vector((0.0, 0.0, 0.0))
    if hole is not None:
        matrix = evaluated(hole)
        origin = to_nullpath(matrix.translation)
        tables["spacetime"] = spacetime_table(hole, matrix)
    tables["camera"] = camera_table(scene, scene.camera, evaluated(scene.camera), origin, width, height)
    settings = scene.nullpath
    tables["render"] = {
        "width": width,
        "height": height,
        "spp": settings.samples,
        "max_depth": settings.max_depth,
        "seed": settings.seed,
    }
    tables["sky"] = sky_table(scene.world, directory, warnings)
    if hole is not None and hole.nullpath.kind == spacetime.WORMHOLE:
        tables["lower.sky"] = {"type": "constant", "radiance": numbers(hole.nullpath.far_side)}
    if hole is not None:
        axis = numbers(to_nullpath(evaluated(hole).to_3x3() @ Vector((0.0, 0.0, 1.0))).normalized())
        disk = accretion_disk_table(hole, axis)
        if disk is not None:
            tables["accretion_disk"] = disk
    return tables, origin


def evaluate_at_render_frame(depsgraph):
    """Evaluates the scene itself (the view layer's evaluation, which the glTF exporter reads) at
    the frame being rendered: an animation render moves only the render's evaluation from frame to
    frame, and edits made since the last redraw (by a script) are not yet evaluated."""
    rendered = depsgraph.scene_eval
    bpy.context.scene.frame_set(rendered.frame_current, subframe=rendered.frame_subframe)


def export(scene, depsgraph, directory):
    """Writes scene.toml, scene.glb and the sky into `directory`; the scene file's path and the
    warnings (what was left out)."""
    warnings = []
    tables, origin = scene_tables(scene, depsgraph, directory, warnings)
    evaluate_at_render_frame(depsgraph)
    gltf = os.path.join(directory, GLTF_FILE)
    export_gltf(gltf)
    if places_anything(gltf):
        tables["objects"] = [{"gltf": GLTF_FILE, "transform": {"translate": numbers(-origin)}}]
    else:
        os.unlink(gltf)  # nothing but the sky renders
    path = os.path.join(directory, SCENE_FILE)
    write_atomically(path, toml_writer.document(tables).encode("utf-8"))
    return path, warnings
