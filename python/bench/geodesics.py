"""Rays per second of ``nullpath.geodesics`` beside ``nullpath bench geodesics``.

The workload is the Rust benchmark's (crates/spacetime/src/fan.rs): a 512² fan of rays with a
40° field of view from a static camera at r = 30 M on the −z axis, looking at a Schwarzschild
hole, traced in the ray's plane with adaptive steps at rtol 1e-8, escape radius 1000 M and at
most 100 000 steps. The script makes the fan's directions, traces them through
``nullpath.geodesics`` (which picks the same in-plane tracer and is handed the same settings),
and runs the program's benchmark in turn with it, on one thread and on all, so that a shared
machine's drift falls on both alike. It prints each one's best rays/s and their ratio.

    python python/bench/geodesics.py [--nullpath PATH] [--size 512] [--rounds 3] [--json]

The program is ``$NULLPATH_BIN``, else the release build in ``$CARGO_TARGET_DIR`` (default
target/).
"""

import argparse
import json
import os
import pathlib
import subprocess
import time

# NumPy's OpenBLAS keeps worker threads spinning for a while after each call (here: the norms of
# the fan's directions). On a machine with few cores they take cycles from the traced rays, so
# they are held to one unless the user says otherwise.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402 (after the BLAS setting, which numpy reads at import)

import nullpath

REPO = pathlib.Path(__file__).resolve().parents[2]


def fan_directions(size, fov_deg=40.0):
    """The unit directions through the pixel centres, row-major, as ``Fan::direction``."""
    half = np.tan(np.radians(fov_deg) / 2)
    i = np.arange(size) + 0.5
    x = (2 * i / size - 1) * half
    y = (1 - 2 * i / size) * half
    xx, yy = np.meshgrid(x, y)  # rows are j (y), columns i (x)
    d = np.stack([xx.ravel(), yy.ravel(), np.ones(size * size)], axis=1)
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def program(explicit):
    if explicit:
        return pathlib.Path(explicit)
    if os.environ.get("NULLPATH_BIN"):
        return pathlib.Path(os.environ["NULLPATH_BIN"])
    return pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target")) / "release" / "nullpath"


def cli_rays_per_second(binary, size):
    """The program's in-plane rays/s by thread count, from one run of its benchmark (best of its
    own three repetitions)."""
    line = [str(binary), "bench", "geodesics", "--size", str(size), "--json"]
    out = json.loads(subprocess.run(line, check=True, capture_output=True, text=True).stdout)
    return {r["threads"]: r["rays_per_second"] for r in out["results"] if r["method"] == "in-plane"}


def python_rays_per_second(spacetime, directions, threads, repeat=3):
    """Best rays/s of ``nullpath.geodesics`` over ``repeat`` runs, arrays in and out."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        nullpath.geodesics(
            spacetime, [0.0, 0.0, -30.0], directions,
            rtol=1e-8, escape_radius=1000.0, max_steps=100_000, threads=threads,
        )
        best = min(best, time.perf_counter() - start)
    return len(directions) / best


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nullpath", help="the nullpath program (default: the release build)")
    parser.add_argument("--size", type=int, default=512, help="rays per side of the fan (default 512)")
    parser.add_argument("--rounds", type=int, default=3, help="turns of program and module (default 3)")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    args = parser.parse_args()
    binary = program(args.nullpath)
    hole = nullpath.Spacetime("schwarzschild", mass=1.0)
    directions = fan_directions(args.size)
    cli, python = {}, {}
    for _ in range(args.rounds):
        for threads, rate in cli_rays_per_second(binary, args.size).items():
            cli[threads] = max(cli.get(threads, 0.0), rate)
            python[threads] = max(python.get(threads, 0.0), python_rays_per_second(hole, directions, threads))
    rows = [
        {"threads": t, "python_rays_per_second": python[t], "cli_rays_per_second": cli[t], "ratio": python[t] / cli[t]}
        for t in sorted(cli)
    ]
    if args.json:
        print(json.dumps({"workload": "geodesics", "fan": args.size, "rays": len(directions), "results": rows}))
        return
    print(f"geodesics: {args.size}² fan, camera at r = 30 M, Schwarzschild, in-plane, rtol 1e-8; best of {args.rounds} rounds")
    print(f"{'threads':>7} {'python rays/s':>14} {'cli rays/s':>12} {'python/cli':>10}")
    for r in rows:
        print(f"{r['threads']:>7} {r['python_rays_per_second']:>14.0f} {r['cli_rays_per_second']:>12.0f} {r['ratio']:>10.3f}")


if __name__ == "__main__":
    main()
