"""The Blender add-on, end to end in a headless Blender:

    blender -b --factory-startup --python-exit-code 1 --python tests/blender/test_addon.py -- \
        --zip nullpath_addon.zip --nullpath target/release/nullpath --workdir DIR

installs the add-on from its zip, adds a black hole beside the default cube with the operator,
renders with the nullpath engine, and checks that the hole's shadow is where Blender projects the
hole, that the cube is lensed (the image differs from the same render with a massless hole), that
the render result holds nullpath's image, and that the exported scene file renders, by the
command line, to the same pixels. Any failed check exits non-zero.
"""

import argparse
import math
import os
import subprocess
import sys
import traceback

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector

WIDTH, HEIGHT, SAMPLES = 96, 72, 4
MASS = 0.12
# Beside the cube (the factory scene's, at the origin, side 2), seen from the factory camera.
HOLE_AT = Vector((-0.5, -2.2, 1.0))
SKY = 0.5  # the world's grey, bright enough that the shadow stands out
RED = (0.8, 0.05, 0.05, 1.0)
GLTF_ADDON = "io_scene_gltf2"
EXTENSION = "bl_ext.user_default.nullpath"  # the manifest's id in Blender's own user repository


def arguments():
    parser = argparse.ArgumentParser()
    parser.add_argument("--zip", required=True)
    parser.add_argument("--nullpath", required=True)
    parser.add_argument("--workdir", required=True)
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1 :] if "--" in sys.argv else [])


def check(condition, message):
    if not condition:
        raise AssertionError(message)
    print(f"ok: {message}")


def install(zip_path, binary):
    """Installs the zip as a legacy add-on (Blender's oldest way, still in 4.2 and later), with
    Blender's glTF exporter off: the add-on turns it on."""
    import addon_utils

    addon_utils.disable(GLTF_ADDON, default_set=True)
    bpy.ops.preferences.addon_install(filepath=os.path.abspath(zip_path), overwrite=True)
    bpy.ops.preferences.addon_enable(module="nullpath_addon")
    check(addon_utils.check(GLTF_ADDON) == (True, True), "the add-on turns Blender's glTF exporter on")
    bpy.context.preferences.addons["nullpath_addon"].preferences.binary = os.path.abspath(binary)
    # Abstract engine bases (Blender 4's HydraRenderEngine) have no bl_idname.
    engines = {getattr(engine, "bl_idname", None) for engine in bpy.types.RenderEngine.__subclasses__()}
    check("NULLPATH" in engines, "the add-on installs from its zip and registers the NULLPATH engine")


def build_scene():
    scene = bpy.context.scene
    check("Cube" in bpy.data.objects and scene.camera is not None, "factory scene has a cube and a camera")
    world = scene.world
    if bpy.app.version < (5, 0, 0):  # from 5.0 a world always uses its nodes
        world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (SKY, SKY, SKY, 1.0)
    background.inputs["Strength"].default_value = 1.0
    # A red cube on the grey sky: its material comes through glTF, and lensing shows in colour.
    bpy.data.objects["Cube"].active_material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = RED
    scene.render.engine = "NULLPATH"
    scene.render.resolution_x, scene.render.resolution_y = WIDTH * 2, HEIGHT * 2
    scene.render.resolution_percentage = 50  # the percentage is applied
    scene.nullpath.samples = SAMPLES
    result = bpy.ops.nullpath.add_black_hole(location=HOLE_AT, mass=MASS)
    check(result == {"FINISHED"}, "Add > nullpath > Black hole")
    hole = bpy.context.active_object
    check(hole.type == "EMPTY" and hole.nullpath.kind == "BLACK_HOLE", "the hole is an Empty with nullpath's parameters")
    check(abs(hole.empty_display_size - 2 * MASS) < 1e-6, "its sphere shows the horizon (2M)")
    return scene, hole


def render(scene, directory):
    """Renders with the engine, keeping the export in `directory`; the render result's pixels."""
    scene.nullpath.export_dir = directory
    bpy.ops.render.render()
    out = os.path.join(directory, "result.exr")
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.color_mode = "OPEN_EXR", "32", "RGB"
    bpy.data.images["Render Result"].save_render(out)
    return Image(out)


class Image:
    """An image's RGB, rows from the bottom as Blender keeps them (Debian's Blender has no numpy)."""

    def __init__(self, path):
        image = bpy.data.images.load(path, check_existing=False)
        image.colorspace_settings.name = "Non-Color"
        self.width, self.height = image.size
        rgba = list(image.pixels)
        bpy.data.images.remove(image)
        self.rgb = [tuple(rgba[i : i + 3]) for i in range(0, len(rgba), 4)]

    def at(self, x, y):
        """Mean of the channels at column x, row y from the bottom."""
        return sum(self.rgb[y * self.width + x]) / 3

    def redness(self, x, y):
        """Red less the mean of green and blue: 0 for the grey sky, large on the red cube."""
        r, g, b = self.rgb[y * self.width + x]
        return r - (g + b) / 2

    def mean(self, xs, ys):
        return sum(self.at(x, y) for x in xs for y in ys) / (len(xs) * len(ys))


def projected(scene, point):
    """Pixel (column, row from the bottom) of a world point."""
    ndc = world_to_camera_view(scene, scene.camera, point)
    return ndc.x * WIDTH, ndc.y * HEIGHT


def shadow_radius_pixels(scene, hole):
    """The shadow's apparent radius: the critical impact parameter 3√3 M seen from the camera."""
    distance = (scene.camera.matrix_world.translation - hole.matrix_world.translation).length
    angle = math.asin(3 * math.sqrt(3) * MASS / distance)
    vertical_fov = 2 * math.atan(math.tan(scene.camera.data.angle / 2) * HEIGHT / WIDTH)
    return math.tan(angle) / math.tan(vertical_fov / 2) * HEIGHT / 2


def check_shadow(image, flat, centre, radius):
    x, y = round(centre[0]), round(centre[1])
    check(3 < radius < 20 and 2 * radius < x < WIDTH - 2 * radius and 2 * radius < y < HEIGHT - 2 * radius,
          f"the hole's shadow (radius {radius:.1f} px) lies inside the image, at ({x}, {y})")
    near = [(x + dx, y + dy) for dx in (-1, 0, 1) for dy in (-1, 0, 1)]
    core = max(image.at(*p) for p in near)
    check(core < 0.01, f"the pixels at the hole's centre are black: at most {core:.4f}")
    flat_core = min(flat.at(*p) for p in near)
    check(flat_core > 0.05, f"without mass they are not: at least {flat_core:.4f}")
    angles = [2 * math.pi * k / 16 for k in range(16)]
    ring = [image.at(round(x + 2 * radius * math.cos(a)), round(y + 2 * radius * math.sin(a))) for a in angles]
    bright = sum(v > 0.05 for v in ring)
    check(bright >= 12, f"around the shadow (twice its radius) the image is bright: {bright} of 16 points")


def check_lensed(scene, image, flat):
    cube = bpy.data.objects["Cube"]
    corners = [projected(scene, cube.matrix_world @ Vector(c)) for c in cube.bound_box]
    x0, x1 = max(0, int(min(c[0] for c in corners))), min(WIDTH, int(max(c[0] for c in corners)) + 1)
    y0, y1 = max(0, int(min(c[1] for c in corners))), min(HEIGHT, int(max(c[1] for c in corners)) + 1)
    xs, ys = range(x0, x1), range(y0, y1)
    centre = ((x0 + x1) // 2, (y0 + y1) // 2)
    check(flat.redness(*centre) > 0.2, f"the cube is red, its Principled BSDF's base colour: {flat.rgb[centre[1] * WIDTH + centre[0]]}")
    red = lambda image: {(x, y) for x in xs for y in ys if image.redness(x, y) > 0.1}  # noqa: E731
    moved = len(red(image) ^ red(flat)) / len(red(flat))
    check(moved > 0.15, f"the cube ({x0}..{x1} × {y0}..{y1}) is lensed: {moved:.0%} of its pixels' area changed between red and not")


def check_round_trip(binary, directory, image):
    """The exported scene file renders by the command line to the engine's pixels, bit for bit."""
    again = os.path.join(directory, "again.exr")
    subprocess.run([binary, "render", os.path.join(directory, "scene.toml"), "--output", again, "--quiet"], check=True)
    engine_exr, cli_exr = Image(os.path.join(directory, "render.exr")), Image(again)
    check(engine_exr.rgb == cli_exr.rgb, "the exported scene renders by `nullpath render` to the same pixels")
    check(image.rgb == engine_exr.rgb, "the render result holds nullpath's image")


def check_progress_and_cancel(directory):
    """The engine's runner reports nullpath's progress up to the whole, and stops it when asked."""
    from nullpath_addon import runner

    scene_file = os.path.join(directory, "scene.toml")
    fractions = []
    runner.run(["render", scene_file, "--output", os.path.join(directory, "progress.exr"), "--progress-lines"],
               fractions.append, lambda: False)
    check(fractions and fractions == sorted(fractions) and fractions[-1] == 1.0,
          f"progress is reported, rising to 1: {len(fractions)} reports, last {fractions[-1] if fractions else None}")
    arguments = ["render", scene_file, "--output", os.path.join(directory, "cancelled.exr"), "--spp", "1048576"]
    try:
        runner.run(arguments, lambda _: None, lambda: True)
    except runner.RunError as error:
        check(str(error) == "cancelled", "a cancelled render stops nullpath")
    else:
        check(False, "a cancelled render stops nullpath")
    check(not os.path.exists(os.path.join(directory, "cancelled.exr")), "and leaves no image")


def check_axes(scene, hole, directory):
    """The exported scene file's frame: Blender's z-up world in nullpath's y-up one, moved so that
    the hole is at the origin, and a spinning hole's axis its local Z."""
    from nullpath_addon import export

    hole.nullpath.spin = MASS / 2
    hole.rotation_euler = (math.radians(90), 0.0, 0.0)  # local Z along Blender's −Y: nullpath's +z
    bpy.context.view_layer.update()
    tables, _ = export.scene_tables(scene, bpy.context.evaluated_depsgraph_get(), directory, [])
    hole.nullpath.spin, hole.rotation_euler = 0.0, (0.0, 0.0, 0.0)
    bpy.context.view_layer.update()
    spacetime = tables["spacetime"]
    check(spacetime["type"] == "kerr" and abs(spacetime["spin"] - MASS / 2) < 1e-6, f"a spinning hole is Kerr's: {spacetime}")
    check(all(abs(a - b) < 1e-6 for a, b in zip(spacetime["axis"], (0, 0, 1))), f"its axis is its local Z, in y-up: {spacetime['axis']}")
    c, h = scene.camera.matrix_world.translation, HOLE_AT
    expected = (c.x - h.x, c.z - h.z, -(c.y - h.y))
    got = tables["camera"]["position"]
    check(all(abs(a - b) < 1e-5 for a, b in zip(got, expected)), f"the camera is placed relative to the hole, y-up: {got}")


def check_animation(scene, image, directory):
    """An animation renders frame by frame, each frame the scene as it is then: frame 1 is the
    still render, and at frame 2 the cube has flown out of the picture."""
    cube = bpy.data.objects["Cube"]
    cube.keyframe_insert("location", frame=1)
    cube.location.z += 100
    cube.keyframe_insert("location", frame=2)
    scene.frame_start, scene.frame_end = 1, 2
    scene.nullpath.export_dir = os.path.join(directory, "animation")
    scene.render.filepath = os.path.join(directory, "frames", "")
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.color_mode = "OPEN_EXR", "32", "RGB"
    bpy.ops.render.render(animation=True)
    first, second = (Image(os.path.join(directory, "frames", f"{n:04}.exr")) for n in (1, 2))
    check(first.rgb == image.rgb, "an animation's frame 1 is the still render")
    red = sum(second.redness(x, y) > 0.1 for x in range(WIDTH) for y in range(HEIGHT))
    check(red == 0, f"at frame 2 the cube has left the picture: {red} red pixels")


def panorama(path):
    """An equirectangular image, green, with a red band at its centre (which Blender shows at +X)
    and blue from there to three quarters (towards −Y)."""
    width, height = 64, 32
    image = bpy.data.images.new("panorama", width, height, float_buffer=True)
    colour = lambda x: (1, 0, 0) if abs(x + 0.5 - width / 2) < 1 else (0, 0, 1) if width / 2 <= x < 3 * width / 4 else (0, 1, 0)  # noqa: E731
    image.pixels = [c for _ in range(height) for x in range(width) for c in (*colour(x), 1.0)]
    image.filepath_raw, image.file_format = path, "OPEN_EXR"
    image.save()
    return image


def check_panorama(scene, hole, directory):
    """An environment texture is the sky, lying as Blender shows it: a camera at the origin looking
    along +X sees the panorama's centre, with −Y (the image's right of centre) to its right."""
    hole.hide_render = True
    bpy.data.objects["Cube"].hide_render = True
    bpy.data.objects["Light"].hide_render = True
    scene.camera.location, scene.camera.rotation_euler = (0, 0, 0), (math.radians(90), 0, math.radians(-90))
    scene.frame_start = scene.frame_end = scene.frame_current = 1
    nodes, links = scene.world.node_tree.nodes, scene.world.node_tree.links
    texture = nodes.new("ShaderNodeTexEnvironment")
    texture.image = panorama(os.path.join(directory, "panorama.exr"))
    links.new(texture.outputs["Color"], nodes["Background"].inputs["Color"])
    sky = render(scene, os.path.join(directory, "panorama"))
    middle = HEIGHT // 2
    seen = [sky.rgb[middle * WIDTH + x] for x in (WIDTH // 2, WIDTH * 3 // 4, WIDTH // 4)]
    dominant = ["RGB"[max(range(3), key=lambda c: rgb[c])] for rgb in seen]
    check(dominant == ["R", "B", "G"], f"the panorama's centre is ahead (+X), −Y to the right: centre, right, left are {dominant}")


def check_extension(zip_path):
    """Blender 4.2 and later also install the zip as an extension (its blender_manifest.toml), in
    place of the legacy add-on."""
    if bpy.app.version < (4, 2, 0):
        return
    bpy.ops.preferences.addon_disable(module="nullpath_addon")
    bpy.ops.extensions.package_install_files(filepath=os.path.abspath(zip_path), repo="user_default", enable_on_install=True)
    check(EXTENSION in bpy.context.preferences.addons, f"the zip installs and enables as the extension {EXTENSION}")
    bpy.context.scene.render.engine = "NULLPATH"
    check(hasattr(bpy.context.preferences.addons[EXTENSION].preferences, "binary") and hasattr(bpy.ops.nullpath, "add_black_hole"),
          "the extension registers the engine, the operators and the preferences")


def main():
    args = arguments()
    print(f"Blender version: {bpy.app.version_string}", flush=True)
    os.makedirs(args.workdir, exist_ok=True)
    install(args.zip, args.nullpath)
    scene, hole = build_scene()
    curved_dir, flat_dir = os.path.join(args.workdir, "curved"), os.path.join(args.workdir, "flat")
    image = render(scene, curved_dir)
    check((image.width, image.height) == (WIDTH, HEIGHT), f"the render is {WIDTH}×{HEIGHT}")
    hole.nullpath.mass = 0.0
    flat = render(scene, flat_dir)
    hole.nullpath.mass = MASS
    check_shadow(image, flat, projected(scene, hole.matrix_world.translation), shadow_radius_pixels(scene, hole))
    check_lensed(scene, image, flat)
    check_round_trip(args.nullpath, curved_dir, image)
    check_progress_and_cancel(curved_dir)
    check_axes(scene, hole, args.workdir)
    check_animation(scene, image, args.workdir)
    check_panorama(scene, hole, args.workdir)
    check_extension(args.zip)


if __name__ == "__main__":
    try:
        main()
    except BaseException:
        traceback.print_exc()
        print("FAILED: tests/blender/test_addon.py", flush=True)
        sys.stdout.flush()
        os._exit(1)  # Blender would otherwise go on and exit 0
    print("PASSED: tests/blender/test_addon.py", flush=True)
