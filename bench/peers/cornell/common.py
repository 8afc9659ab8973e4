"""Shared helpers for the Cornell-box peer comparison: run one render as a child process (nice -n 19),
measure its wall and CPU time, read its image back as a float64 H x W x 3 array."""
import json
import os
import shlex
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", "..", ".."))
SCENE = os.path.join(REPO, "scenes", "cornell-box.toml")
MI_WORKER = os.path.join(HERE, "mi_cornell.py")
NULLPATH = os.environ.get("NULLPATH", "/tmp/nullpath-cornell")
RUN_DIR = os.environ.get("CORNELL_RUN_DIR", "/work/peers-run/cornell")
# extra flags for every `nullpath render` (e.g. NULLPATH_ARGS=--spectral); the scripts' --spectral adds it too
NULLPATH_ARGS = shlex.split(os.environ.get("NULLPATH_ARGS", ""))
NICE = ["nice", "-n", "19"]
os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")

_bitmap_ready = False


def read_exr(path):
    """nullpath's EXR (linear RGB float32) through Mitsuba's Bitmap (no extra package)."""
    global _bitmap_ready
    import mitsuba as mi
    if not _bitmap_ready:
        mi.set_variant("scalar_rgb")
        _bitmap_ready = True
    return np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]


def timed(cmd):
    """Run cmd; return (stdout, wall seconds). CPU time: RUSAGE_CHILDREN deltas around it."""
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out, err = p.communicate()
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        sys.stderr.write(err.decode(errors="replace"))
        raise RuntimeError("failed (%d): %s" % (p.returncode, " ".join(cmd)))
    return out.decode(), wall


def _child_cpu():
    import resource
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_nullpath(spp, threads, seed, res, out_exr, extra_args=()):
    """One `nullpath render` of the Cornell box; returns a record with wall/cpu/render times.
    extra_args (and $NULLPATH_ARGS) are appended to the command line, e.g. ["--spectral"]."""
    stats = out_exr + ".stats.json"
    args = list(NULLPATH_ARGS) + [x for x in extra_args if x not in NULLPATH_ARGS]
    cmd = NICE + [NULLPATH, "render", SCENE, "--width", str(res), "--height", str(res),
                  "--spp", str(spp), "--seed", str(seed), "--threads", str(threads),
                  "--quiet", "--stats", stats, "-o", out_exr] + args
    c0 = _child_cpu()
    _, wall = timed(cmd)
    cpu = _child_cpu() - c0
    with open(stats) as f:
        st = json.load(f)
    render_s = st["seconds"]
    return {"renderer": "nullpath", "variant": "nullpath-spectral" if "--spectral" in args else "nullpath",
            "sampler": "sobol-owen", "spp": st["spp"], "args": args,
            "threads": threads, "seed": seed, "wall_s": wall, "cpu_s": cpu, "render_s": render_s,
            "startup_s": wall - render_s, "image": out_exr, "cmd": " ".join(cmd)}


def run_mitsuba(variant, sampler, spp, threads, seed, res, out_npy, rr_depth=2, python=sys.executable):
    """One Mitsuba render in a fresh process (python import + scene load + JIT counted in wall)."""
    cmd = NICE + [python, MI_WORKER, "--variant", variant, "--sampler", sampler, "--spp", str(spp),
                  "--threads", str(threads), "--seed", str(seed), "--res", str(res),
                  "--rr-depth", str(rr_depth), "--out", out_npy]
    c0 = _child_cpu()
    out, wall = timed(cmd)
    cpu = _child_cpu() - c0
    line = [x for x in out.splitlines() if x.startswith("MI_RESULT ")][-1]
    rec = json.loads(line[len("MI_RESULT "):])
    rec.update({"wall_s": wall, "cpu_s": cpu, "startup_s": wall - rec["render_s"], "image": out_npy,
                "cmd": " ".join(cmd)})
    return rec


def load_image(rec_or_path):
    p = rec_or_path["image"] if isinstance(rec_or_path, dict) else rec_or_path
    return np.load(p).astype(np.float64) if p.endswith(".npy") else read_exr(p)


def rmse(img, ref):
    return float(np.sqrt(np.mean((img - ref) ** 2)))
