"""The Scene API: scenes read, edited and rendered from Python, against the `nullpath` program.

Every scene is written by the test into its temporary folder: a small Schwarzschild scene (curved
spacetime, so the geodesic integrator and the lensing are in the comparison) with a sky, a lit
floor, a ball and data channels.
"""

import _thread
import json
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import nullpath

SCENE = """\
# A small black-hole scene for the tests.
[spacetime]
type = "schwarzschild"
mass = 0.3

[camera]
position = [0, 1, 8]
look_at = [0, 0, 0]
fov = 40

[render]
width = 24
height = 16
spp = 4
seed = 7
channels = ["redshift", "fate"]

[sky]
type = "constant"
radiance = [0.15, 0.3, 0.8]

[[objects]]
shape = { type = "sphere", center = [2, 0, 0], radius = 0.7 }
material = { type = "diffuse", reflectance = [0.8, 0.2, 0.2] }

[[objects]]
shape = { type = "plane", point = [0, -1, 0], normal = [0, 1, 0] }
material = { type = "diffuse", reflectance = [0.6, 0.6, 0.6] }
"""


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(SCENE)
    return path


def cli_render(nullpath_bin, scene_file, out, *flags):
    """The program's EXR of `scene_file` with `flags`: its image, channels and statistics."""
    stats = out.with_suffix(".json")
    subprocess.run(
        [str(nullpath_bin), "render", str(scene_file), "-o", str(out), "--stats", str(stats), "--quiet", *flags],
        check=True,
    )
    image, channels = nullpath.read_exr(out)
    return image, channels, json.loads(stats.read_text())


def test_render_equals_the_programs_exr_bit_for_bit(nullpath_bin, scene_file, tmp_path):
    image, channels, stats = cli_render(nullpath_bin, scene_file, tmp_path / "cli.exr", "--seed", "3", "--spp", "8")
    result = nullpath.Scene.load(scene_file).render(seed=3, spp=8, progress=False)
    assert result.image.dtype == np.float32 and result.image.shape == (16, 24, 3)
    assert np.array_equal(result.image, image, equal_nan=True)
    assert result.channels.keys() == channels.keys() == {"redshift", "fate"}
    for name in channels:
        assert np.array_equal(result.channels[name], channels[name], equal_nan=True), name
    assert result.image.max() > 0, "something is seen"
    # The same fields as --stats; the counts equal (the seconds are the run's own).
    assert result.stats.keys() == stats.keys()
    for key in ["rays", "samples", "fates", "width", "height", "spp", "spp_min", "spp_max", "outcome", "complete"]:
        assert result.stats[key] == stats[key], key


def test_the_image_does_not_depend_on_the_thread_count(scene_file):
    scene = nullpath.Scene.load(scene_file)
    one = scene.render(threads=1, progress=False).image
    two = scene.render(threads=2, progress=False).image
    assert np.array_equal(one, two, equal_nan=True)
    with pytest.raises(ValueError, match="threads"):
        scene.render(threads=0, progress=False)


def test_a_malformed_scene_names_file_line_and_field(scene_file):
    scene_file.write_text(SCENE.replace("fov = 40", "fov = 200"))
    with pytest.raises(nullpath.SceneError) as error:
        nullpath.Scene.load(scene_file)
    assert str(error.value) == f"{scene_file}:9:7: camera.fov: must be in (0, 180) degrees, got 200"
    assert isinstance(error.value, ValueError)
    with pytest.raises(nullpath.SceneError, match=r"^<string>:2:1: .*unknown"):
        nullpath.Scene.from_toml("[camera]\nzoom = 3\n")


def test_invalid_settings_are_refused_with_the_field_and_the_scene_kept(scene_file):
    scene = nullpath.Scene.load(scene_file)
    with pytest.raises(nullpath.SceneError, match=r"camera\.fov: must be in \(0, 180\) degrees, got 200"):
        scene.camera["fov"] = 200
    assert scene.camera["fov"] == 40, "the scene is as it was"
    scene.spacetime.update(type="kerr", spin=0.1)  # a Kerr hole needs its spin: set together
    with pytest.raises(nullpath.SceneError, match=r"spacetime.*spin"):
        scene.spacetime["spin"] = 0.9  # |spin| > mass
    scene.spacetime.update(mass=1.0, spin=0.9)  # valid together
    assert scene.spacetime.to_dict() == {"type": "kerr", "mass": 1.0, "spin": 0.9}
    with pytest.raises(nullpath.SceneError, match=r"render\.width"):
        scene.render(width=0, progress=False)
    with pytest.raises(TypeError, match="camera.up"):
        scene.camera["up"] = None


def test_properties_round_trip_and_change_the_render(nullpath_bin, scene_file, tmp_path):
    scene = nullpath.Scene.load(scene_file)
    assert scene.camera["position"] == [0, 1, 8]
    assert scene.settings["spp"] == 4 and "max_depth" not in scene.settings
    before = scene.render(progress=False).image
    scene.camera["fov"] = 25.5
    scene.settings.update(width=12, height=10)
    assert scene.camera["fov"] == 25.5 and scene.settings["width"] == 12
    assert "# A small black-hole scene" in scene.toml, "the author's text is kept"
    after = scene.render(progress=False).image
    assert after.shape == (10, 12, 3) and before.shape == (16, 24, 3)
    # The edited scene renders as the program renders the edited file.
    edited = tmp_path / "edited.toml"
    edited.write_text(scene.toml)
    image, _, _ = cli_render(nullpath_bin, edited, tmp_path / "edited.exr")
    assert np.array_equal(after, image, equal_nan=True)
    del scene.camera["fov"]
    assert "fov" not in scene.camera
    # The same scene from a dict, and views.
    document = scene.to_dict()
    document["views"] = {"top": {"position": [0, 9, 0.1], "look_at": [0, 0, 0]}}
    again = nullpath.Scene.from_dict(document, base_dir=tmp_path)
    assert again.views == ["top"] and again.view is None
    again.view = "top"
    assert again.camera["position"] == [0, 9, 0.1]
    with pytest.raises(nullpath.SceneError, match="nowhere"):
        again.view = "nowhere"
    assert again.view == "top"


def test_relative_files_resolve_against_the_scenes_folder(tmp_path):
    folder = tmp_path / "inside"
    folder.mkdir()
    (folder / "tri.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    text = SCENE + '\n[[objects]]\nshape = { type = "mesh", file = "tri.obj" }\nmaterial = { type = "diffuse", reflectance = [1, 1, 1] }\n'
    (folder / "scene.toml").write_text(text)
    nullpath.Scene.load(folder / "scene.toml")
    nullpath.Scene.from_toml(text, base_dir=folder)
    with pytest.raises(nullpath.SceneError, match="tri.obj"):
        nullpath.Scene.from_toml(text, base_dir=tmp_path)


def long_render(scene_file):
    """A render of a few seconds at least."""
    scene = nullpath.Scene.load(scene_file)
    scene.settings.update(width=160, height=120, spp=4096)
    return scene


def test_other_threads_run_while_it_renders(scene_file):
    scene = nullpath.Scene.load(scene_file)
    scene.settings.update(width=96, height=64, spp=64)
    count = 0
    stop = threading.Event()

    def counter():
        nonlocal count
        while not stop.is_set():
            count += 1

    thread = threading.Thread(target=counter)
    thread.start()
    try:
        ticks = []
        scene.render(threads=1, progress=lambda done, total: ticks.append(count))
    finally:
        stop.set()
        thread.join()
    # While it rendered, the counter went on between the progress reports: the GIL was free.
    assert len(ticks) >= 2, "the render reported its progress"
    assert ticks[-1] - ticks[0] > 10000, ticks


@pytest.fixture
def ctrl_c_raises():
    """Ctrl-C raises KeyboardInterrupt, as in a terminal or a notebook. A process started in the
    background by a shell without job control inherits SIGINT ignored, and Python then leaves it
    ignored (and `_thread.interrupt_main` does nothing); CI may start pytest so."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, previous)


def test_an_interrupt_stops_the_render_within_a_second(scene_file, ctrl_c_raises):
    scene = long_render(scene_file)
    timer = threading.Timer(0.3, _thread.interrupt_main)
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(progress=False)
    stopped = time.monotonic() - start
    timer.join()
    assert stopped < 0.3 + 1.0, stopped
    # The module goes on working.
    assert scene.render(width=8, height=6, spp=1, progress=False).image.shape == (6, 8, 3)


def test_progress_goes_to_a_callable_and_its_exception_stops_the_render(scene_file):
    scene = nullpath.Scene.load(scene_file)
    seen = []
    scene.render(progress=lambda done, total: seen.append((done, total)))
    assert seen and seen[-1] == (seen[-1][1], seen[-1][1]) and seen[-1][1] == 24 * 16 * 4

    def refuse(done, total):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        long_render(scene_file).render(progress=refuse)


def test_read_exr_reads_what_the_program_wrote(nullpath_bin, scene_file, tmp_path):
    image, channels, _ = cli_render(nullpath_bin, scene_file, tmp_path / "x.exr")
    assert image.shape == (16, 24, 3) and image.dtype == np.float32
    assert set(np.unique(channels["fate"])) <= {0.0, 2.0, 4.0}
    with pytest.raises(ValueError, match="OpenEXR"):
        nullpath.read_exr(tmp_path / "missing.exr")
