"""The nullpath render engine: export, run `nullpath render`, load the EXR into the render result."""

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
        result = self.begin_result(0, 0, width, height)
        result.layers[0].load_from_file(image)
        self.end_result(result)


def thread_arguments(scene):
    """`--threads N` where Blender's render threads are fixed, else nullpath takes every core."""
    render = scene.render
    return ["--threads", str(render.threads)] if render.threads_mode == "FIXED" else []


def register():
    bpy.utils.register_class(NullpathRenderEngine)


def unregister():
    bpy.utils.unregister_class(NullpathRenderEngine)
