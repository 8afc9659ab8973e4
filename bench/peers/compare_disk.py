#!/usr/bin/env python3
"""Compares nullpath's redshift channel of a thin-disk image with a peer's g map (disk.py).

nullpath renders the disk with a static pinhole camera at distance D (scene file), writing the
`redshift` and `disk_radius` data channels into an EXR (`[render] channels`). The peers' g is
for an observer at infinity; a static observer at Boyer–Lindquist radius D and inclination i
measures frequencies 1/sqrt(-g_tt) times higher, so nullpath's g is multiplied by
sqrt(1 - 2 M D / (D^2 + a^2 cos^2 i)) before comparing.

    python3 compare_disk.py NULLPATH.exr PEER_DIR --distance 1e4 --spin 0.9 --incl 80

Needs numpy and OpenEXR (pip install OpenEXR). Prints a JSON summary: pixels where both see the
disk, where only one does, max and median |dg|, and the same for the disk radius hit.
"""
import argparse
import json
import math
import sys

import numpy as np
import OpenEXR
import Imath


def channel(exr, name):
    header = exr.header()
    window = header["dataWindow"]
    width, height = window.max.x - window.min.x + 1, window.max.y - window.min.y + 1
    raw = exr.channel(name, Imath.PixelType(Imath.PixelType.FLOAT))
    return np.frombuffer(raw, dtype=np.float32).reshape(height, width).astype(np.float64)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("exr")
    parser.add_argument("peer_dir")
    parser.add_argument("--distance", type=float, required=True, help="nullpath's camera distance, M")
    parser.add_argument("--spin", type=float, required=True)
    parser.add_argument("--incl", type=float, required=True, help="degrees from the spin axis")
    parser.add_argument("--mass", type=float, default=1.0)
    args = parser.parse_args()
    exr = OpenEXR.InputFile(args.exr)
    g = channel(exr, "redshift")
    r = channel(exr, "disk_radius")
    m, a, d, i = args.mass, args.spin, args.distance, math.radians(args.incl)
    lapse = math.sqrt(1.0 - 2.0 * m * d / (d * d + (a * math.cos(i)) ** 2))
    ours = np.where(np.isfinite(r), g * lapse, np.nan)
    peer_g = np.load(f"{args.peer_dir}/g.npy")
    peer_r = np.load(f"{args.peer_dir}/r_emit.npy")
    if peer_g.shape != ours.shape:
        sys.exit(f"sizes differ: nullpath {ours.shape}, peer {peer_g.shape}")
    both = np.isfinite(ours) & np.isfinite(peer_g)
    dg = np.abs(ours[both] - peer_g[both])
    dr = np.abs(r[both] - peer_r[both])
    worst = np.unravel_index(np.argmax(np.where(both, np.abs(ours - peer_g), -1.0)), ours.shape)
    print(json.dumps({
        "pixels": int(ours.size),
        "both_see_the_disk": int(both.sum()),
        "only_nullpath": int((np.isfinite(ours) & ~np.isfinite(peer_g)).sum()),
        "only_peer": int((~np.isfinite(ours) & np.isfinite(peer_g)).sum()),
        "max_abs_dg": float(dg.max()) if dg.size else None,
        "median_abs_dg": float(np.median(dg)) if dg.size else None,
        "pixels_dg_over_1e-3": int((dg > 1e-3).sum()),
        "worst_pixel_row_col": [int(worst[0]), int(worst[1])],
        "max_abs_dr": float(dr.max()) if dr.size else None,
        "median_abs_dr": float(np.median(dr)) if dr.size else None,
    }, indent=2))


if __name__ == "__main__":
    main()
