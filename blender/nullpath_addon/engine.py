"""The nullpath render engine: export, run `nullpath render`, load the EXR into the render result."""

import array
import os
import shutil
import tempfile

import bpy

from . import export, runner

IMAGE_FILE = "render.exr"


class NullpathRenderEngine(bpy.types.RenderEngine):
    bl_idname = "NULLPATH"
    bl_label = "nullpath"
    bl_use_preview = False

    def render(self, depsgraph):
        scene = depsgraph.scene
        kept = bpy.path.abspath(scene.nullpath.export_dir) if scene.nullpath.export_dir else ""
        directory = kept or tempfile.mkdtemp(prefix="nullpath-blender-")
        try:
            if kept:
                os.makedirs(kept, exist_ok=True)
            self.render_into(scene, depsgraph, directory)
        except (export.ExportError, runner.RunError, OSError) as error:
            if str(error) != "cancelled":
                self.report({"ERROR"}, f"nullpath: {error}")
        finally:
            if not kept:
                shutil.rmtree(directory, ignore_errors=True)

    def render_into(self, scene, depsgraph, directory):
        self.update_stats("", "nullpath: exporting the scene")
        scene_file, warnings = export.export(scene, depsgraph, directory)
        for warning in warnings:
            self.report({"WARNING"}, f"nullpath: {warning}")
        self.update_stats("", "nullpath: rendering")
        image = os.path.join(directory, IMAGE_FILE)
        messages = runner.run(
            ["render", scene_file, "--output", image, "--progress-lines", *thread_arguments(scene)],
            self.update_progress,
            self.test_break,
        )
        for line in messages.splitlines():
            if line.startswith("warning"):
                self.report({"WARNING"}, f"nullpath: {line}")
        width, height = export.resolution(scene)
        pixels = read_rgba(image, width, height)
        result = self.begin_result(0, 0, width, height)
        fill_pass(result.layers[0].passes["Combined"], pixels)
        self.end_result(result)


def read_rgba(path, width, height):
    """The image at `path` as flat RGBA floats, rows from the bottom, as Blender reads it: the
    render pass is filled from them rather than by `RenderLayer.load_from_file`, which Blender 4
    restricts to files whose channels are named as a render's (`Combined.R`), not nullpath's `R`."""
    image = bpy.data.images.load(path, check_existing=False)
    try:
        image.colorspace_settings.name = "Non-Color"  # the values as written, no conversion
        if tuple(image.size) != (width, height):
            raise runner.RunError(f"nullpath wrote a {image.size[0]}×{image.size[1]} image, not {width}×{height}")
        pixels = array.array("f", bytes(4 * 4 * width * height))
        image.pixels.foreach_get(pixels)
        return pixels
    finally:
        bpy.data.images.remove(image)


def fill_pass(render_pass, pixels):
    """Copies flat RGBA `pixels` into a render pass. Blender 4.2 and later take them flat; before,
    the pass's `rect` is set pixel by pixel (its `foreach_set` wants one item per pixel, and a
    shaped buffer crashes Blender 3.4)."""
    if bpy.app.version >= (4, 2, 0):
        render_pass.rect.foreach_set(pixels)
    else:
        render_pass.rect = [pixels[i : i + 4] for i in range(0, len(pixels), 4)]


def thread_arguments(scene):
    """`--threads N` where Blender's render threads are fixed, else nullpath takes every core."""
    render = scene.render
    return ["--threads", str(render.threads)] if render.threads_mode == "FIXED" else []


def register():
    bpy.utils.register_class(NullpathRenderEngine)


def unregister():
    bpy.utils.unregister_class(NullpathRenderEngine)
