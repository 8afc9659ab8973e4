#!/usr/bin/env python3
"""Thin Novikov-Thorne / Page-Thorne disc around a Kerr black hole, rendered by
two peer codes (kerrz, Gyoto) on one common image plane, for comparison with
nullpath.

Run it with Debian's /usr/bin/python3 (it has numpy and Gyoto's bindings);
kerrz's Python API runs in its own venv, which this script calls as a
subprocess (the same file, in a hidden worker mode).

  /usr/bin/python3 bench/peers/disk.py --spin 0.9 --incl 80 --rout 20 \
      --npix 128 --half-width 25 --out /work/peers-run/out/a0.9_i80_N128 \
      --kerrz-python /work/peers-run/venv2/bin/python

Common image plane (every array written here uses it):
  * N x N pixels, pixel centres (no pixel on the edge):
      alpha[c] = -L + (c + 0.5) * 2L/N        (column c = 0 .. N-1)
      beta[r]  = +L - (r + 0.5) * 2L/N        (row r = 0 .. N-1)
    alpha, beta are Bardeen's impact parameters at infinity in units of M:
      alpha = -lambda / sin(i),  beta = +-sqrt(Theta(i)) = p_theta / E
      (lambda = L_z/E, Theta = eta + a^2 cos^2 i - lambda^2 cot^2 i,
       beta > 0 where the arriving photon has dtheta/dlambda > 0).
  * row 0 is the top of the picture (beta = +L side, the direction of the
    spin axis projected on the sky), column 0 is the left (alpha = -L).
    The picture is the sky as the observer sees it (not mirrored): right
    is +e_phi at the observer (where prograde gas on the near side moves).
    For a > 0 the gas (prograde, +phi) approaches the observer on the
    LEFT (alpha < 0, g > 1) and recedes on the right.
  * observer: Boyer-Lindquist theta = i (from the +z spin axis, 0 < i < 90
    is above the disc's upper face), phi = 0, static (u = e_t/sqrt(-g_tt)).

Per peer, under OUT/<peer>/:
  g.npy           float64 N x N, g = nu_obs / nu_emit (1 + z = 1/g),
                  NaN where the first image does not land on the disc.
  r_emit.npy      float64 N x N, Boyer-Lindquist radius of the disc hit.
  I_pt.npy        float64 N x N, Page-Thorne bolometric intensity
                  g^4 F(r) / pi, F the Page-Thorne flux with M = Mdot = 1
                  (Gyoto: its own 'User4' quantity; kerrz: computed here
                  from kerrz's g and r with the same closed form).
  conventions.json  camera, orientation, definitions, timings.
  g.png           the g map (grey: g_min..g_max, blue: no disc).
Plus OUT/compare.json (kerrz vs Gyoto |dg|) and OUT/dg.png.

Only a >= 0 is supported: for a < 0 with prograde gas, render |a| and
mirror left-right (alpha -> -alpha).
"""
import argparse
import json
import math
import os
import platform
import resource
import struct
import subprocess
import sys
import time
import zlib

import numpy as np

DEFAULT_KERRZ_PY = "/work/peers-run/venv2/bin/python"
B_ORDER_CHECK = 9.0     # M; the Kerr critical curve lies within b < 7 M


# ----------------------------------------------------------------- physics --

def isco(a):
    """Prograde ISCO radius (Bardeen, Press & Teukolsky 1972), M = 1."""
    z1 = 1 + (1 - a * a) ** (1 / 3) * ((1 + a) ** (1 / 3) + (1 - a) ** (1 / 3))
    z2 = math.sqrt(3 * a * a + z1 * z1)
    return 3 + z2 - math.sqrt((3 - z1) * (3 + z1 + 2 * z2))


def pt_flux(r, a):
    """Page & Thorne (1974) flux F(r) from the face of the disc, M = Mdot = 1,
    zero-torque inner edge at the ISCO: F = 3/(8 pi) f(x) with x = sqrt(r),
    f = [x - x0 - 3a/2 ln(x/x0) - sum_k 3 (xk - a)^2 / (xk prod (xk - xj))
         ln((x - xk)/(x0 - xk))] / (x^4 (x^3 - 3x + 2a))."""
    x = np.sqrt(np.asarray(r, dtype=np.float64))
    x0 = math.sqrt(isco(a))
    c = math.acos(a) / 3
    xs = [2 * math.cos(c - math.pi / 3), 2 * math.cos(c + math.pi / 3),
          -2 * math.cos(c)]
    br = x - x0 - 1.5 * a * np.log(x / x0)
    for k in range(3):
        xk = xs[k]
        den = xk
        for j in range(3):
            if j != k:
                den *= xk - xs[j]
        br = br - 3 * (xk - a) ** 2 / den * np.log((x - xk) / (x0 - xk))
    return 3 / (8 * math.pi) * br / (x ** 4 * (x ** 3 - 3 * x + 2 * a))


def grid(n, half):
    """Pixel-centre alpha (per column) and beta (per row, top row first)."""
    d = 2.0 * half / n
    alpha = -half + (np.arange(n) + 0.5) * d
    return alpha, alpha[::-1].copy()


def kerr_bl(r, th, a):
    s2 = math.sin(th) ** 2
    sig = r * r + a * a * math.cos(th) ** 2
    gtt = -(1 - 2 * r / sig)
    gtp = -2 * a * r * s2 / sig
    gpp = (r * r + a * a + 2 * a * a * r * s2 / sig) * s2
    return gtt, gtp, gpp, sig


# ----------------------------------------------------------------- output --

def write_png(path, rgb):
    rgb = np.ascontiguousarray(rgb, dtype=np.uint8)
    h, w = rgb.shape[:2]
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def map_png(path, img, lo=None, hi=None, diverging=False, scale=1):
    """Grey map of img (row 0 = top; dark = min, white = max), NaN in blue.
    diverging: white at 0, red > 0, blue < 0, saturating at +-hi; NaN grey."""
    fin = np.isfinite(img)
    out = np.zeros(img.shape + (3,), np.uint8)
    out[~fin] = (45, 45, 45) if diverging else (20, 40, 110)
    if fin.any():
        v = img[fin]
        if diverging:
            hi = hi or max(np.abs(v).max(), 1e-300)
            t = np.clip(v / hi, -1, 1)
            col = np.stack([255 * (1 - np.clip(-t, 0, 1)),
                            255 * (1 - np.abs(t)),
                            255 * (1 - np.clip(t, 0, 1))], -1)
        else:
            lo = v.min() if lo is None else lo
            hi = v.max() if hi is None else hi
            t = np.clip((v - lo) / max(hi - lo, 1e-300), 0, 1)
            col = np.repeat((40 + 215 * t)[:, None], 3, 1)
        out[fin] = (col + 0.5).astype(np.uint8)
    if scale > 1:
        out = np.repeat(np.repeat(out, scale, 0), scale, 1)
    write_png(path, out)


def timed(cmd, **kw):
    """Run cmd; return (CompletedProcess, wall s, user s, sys s, maxrss MB)."""
    r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    wall = time.perf_counter() - t0
    r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.stderr.write(p.stdout[-3000:] + p.stderr[-3000:])
        raise SystemExit("command failed (%d): %s" % (p.returncode, " ".join(cmd)))
    return (p, wall, r1.ru_utime - r0.ru_utime, r1.ru_stime - r0.ru_stime,
            r1.ru_maxrss / 1024.0)


def _num(x):
    """float for JSON, None for NaN."""
    return float(x) if np.isfinite(x) else None


def machine():
    try:
        model = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo")
                 if l.startswith("model name")][0]
    except Exception:
        model = platform.processor()
    return {"cpu": model, "cores": os.cpu_count(),
            "loadavg_before": open("/proc/loadavg").read().split()[:3],
            "date_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "host_os": platform.platform()}


def image_plane_json(n, half):
    d = 2.0 * half / n
    return {
        "npix": n, "half_width_M": half, "pixel_size_M": d,
        "pixel_centre": "alpha[col] = -L + (col + 0.5) * 2L/N; "
                        "beta[row] = +L - (row + 0.5) * 2L/N  (L = half_width_M)",
        "alpha_first_last": [-half + 0.5 * d, half - 0.5 * d],
        "beta_first_last": [half - 0.5 * d, -half + 0.5 * d],
        "array_layout": "numpy float64 [row, col], C order",
        "row_0": "beta = +L (top of the picture; the side the projected "
                 "+z spin axis points to)",
        "col_0": "alpha = -L (left of the picture)",
        "handedness": "sky as seen by the observer (not mirrored): right "
                      "(alpha > 0) is +e_phi at the observer, up (beta > 0) "
                      "is -e_theta (towards +z)",
        "alpha_beta_definition": "Bardeen impact parameters at infinity, units "
                                 "of M: alpha = -lambda/sin(i), beta = p_theta/E "
                                 "at the observer (lambda = L_z/E); beta > 0 where "
                                 "the arriving photon has dtheta/dlambda > 0",
        "approaching_side": "for a > 0 the prograde gas approaches on the left "
                            "(alpha < 0, g > 1) and recedes on the right",
    }


def pinhole_json(n, half, dist, incl):
    tan_half = half / dist
    return {
        "observer_r_M": dist, "observer_theta_deg": incl, "observer_phi": 0.0,
        "observer_frame": "static (u = e_t / sqrt(-g_tt)), orthonormal legs "
                          "e_r/sqrt(g_rr), e_theta/sqrt(g_thth), e_phi/sqrt(g_phph)",
        "projection": "rectilinear (pinhole, flat focal plane)",
        "fov_full_rad": 2 * math.atan(tan_half),
        "tan_half_fov": tan_half,
        "pixel_direction": "x = alpha[col]/D, y = beta[row]/D (focal-plane "
                           "coordinates, tan of the angle); the light of that "
                           "pixel appears to come from the local direction "
                           "n = (-e_r + x e_phi - y e_theta)/sqrt(1 + x^2 + y^2)",
        "note": "alpha = D x and beta = D y up to relative O(M/D) (here %.1e) "
                "and O(x^2) (here %.1e)" % (1.0 / dist, tan_half ** 2),
    }


# ------------------------------------------------------------------ kerrz --

def save_maps(folder, **maps):
    """Each per-pixel map as NAME.npy in `folder` (what compare_disk.py reads)."""
    for name, values in maps.items():
        np.save(os.path.join(folder, name + ".npy"), values)


def kerrz_worker(a):
    """Runs inside kerrz's venv: trace the common grid with kerrz's Python
    API and write g, r to the given folder."""
    from kerrz.py import (KerrMetric, FourVector, NullGeodesic,
                          circular_orbit_velocity, Status)
    n, half, incl, rin, rout, robs, out = (a.npix, a.half_width, a.incl,
                                           a.rin, a.rout, a.kerrz_robs, a.out)
    alphas = np.load(os.path.join(out, "_alpha.npy"))
    betas = np.load(os.path.join(out, "_beta.npy"))
    m = KerrMetric(1.0, a.spin)
    x0 = FourVector(r=robs, theta=math.radians(incl))
    vobs = FourVector(t=1.0, r=0.0, theta=0.0, phi=0.0).normalise_at(m, x0, -1.0)
    ny, nx = betas.size, alphas.size
    g = np.full((ny, nx), np.nan)
    r = np.full((ny, nx), np.nan)
    st = np.zeros((ny, nx), np.int8)
    t0 = time.perf_counter()
    c0 = time.process_time()
    for row, b in enumerate(betas):
        for col, al in enumerate(alphas):
            geo = NullGeodesic.from_impact_parameters(m, float(al), float(b), x0)
            res = geo.trace_to_angle(math.pi / 2)   # first equatorial crossing
            st[row, col] = res.status.value
            if res.status == Status.NONE and rin <= res.r <= rout:
                vf = circular_orbit_velocity(m, res.r)
                g[row, col] = geo.energyshift(vobs, res.to_four_vec(), vf)
                r[row, col] = res.r
    np.save(os.path.join(out, "_g.npy"), g)
    np.save(os.path.join(out, "_r.npy"), r)
    np.save(os.path.join(out, "_status.npy"), st)
    json.dump({"wall_s": time.perf_counter() - t0, "cpu_s": time.process_time() - c0},
              open(os.path.join(out, "_time.json"), "w"))


def read_kerrz_table(path):
    """kerrz --save writes a FITS BINTABLE of float32 columns."""
    buf = open(path, "rb").read()
    off, hdrs = 0, []
    for _ in range(2):
        cards = []
        while True:
            blk = buf[off:off + 2880]
            off += 2880
            cards += [blk[k:k + 80].decode("ascii") for k in range(0, 2880, 80)]
            if any(c[:8].strip() == "END" for c in cards[-36:]):
                break
        kv = {}
        for c in cards:
            if c[8:10] == "= ":
                kv[c[:8].strip()] = c[10:].split("/")[0].strip().strip("'").strip()
        hdrs.append(kv)
    kv = hdrs[1]
    names = [kv["TTYPE%d" % k] for k in range(1, int(kv["TFIELDS"]) + 1)]
    dt = np.dtype([(nm, ">f4") for nm in names])
    rows = int(kv["NAXIS2"])
    return np.frombuffer(buf[off:off + dt.itemsize * rows], dtype=dt), kv


def run_kerrz(a, out, rin):
    kdir = os.path.join(out, "kerrz")
    os.makedirs(kdir, exist_ok=True)
    n, half = a.npix, a.half_width
    alpha, beta = grid(n, half)
    np.save(os.path.join(kdir, "_alpha.npy"), alpha)
    np.save(os.path.join(kdir, "_beta.npy"), beta)
    info = {"peer": "kerrz", "machine": machine(), "timings": []}
    kpy = a.kerrz_python
    ver = subprocess.run([kpy, "-c", "import importlib.metadata as m;"
                          "print(m.version('kerrz'))"], capture_output=True,
                         text=True).stdout.strip()
    info["version"] = "kerrz " + ver

    # 1. The data product: kerrz's Python API (libkerrz, elliptic-integral
    #    geodesics) on the exact common grid, float64.
    cmd = [kpy, os.path.abspath(__file__), "--_kerrz-worker", "--spin", repr(a.spin),
           "--incl", repr(a.incl), "--rout", repr(a.rout), "--rin", repr(rin),
           "--npix", str(n), "--half-width", repr(half), "--kerrz-robs",
           repr(a.kerrz_robs), "--out", kdir]
    _, wall, usr, sy, rss = timed(cmd)
    inner = json.load(open(os.path.join(kdir, "_time.json")))
    info["timings"].append({
        "what": "kerrz Python API (ctypes -> libkerrz), one geodesic per pixel, "
                "python loop, 1 thread, exact common grid",
        "command": " ".join(cmd), "npix": n, "threads": 1,
        "process_wall_s": wall, "process_user_s": usr, "process_sys_s": sy,
        "loop_wall_s": inner["wall_s"], "loop_cpu_s": inner["cpu_s"],
        "maxrss_children_so_far_MB": rss})
    g = np.load(os.path.join(kdir, "_g.npy"))
    r = np.load(os.path.join(kdir, "_r.npy"))

    # 2. kerrz's own image renderer (kerrzcli image) for timing and as a check
    #    that (1) reproduces it. kerrzcli renders 2*res*floor(A) pixels per
    #    side (res an integer) on linspace(-A, A, n), so it cannot produce the
    #    common grid in general; use res | N/2 with A = N/(2 res) as close to
    #    L as possible: the same pixel count on a slightly different plane.
    if n % 2:
        raise SystemExit("kerrzcli needs an even npix")
    res = min((r_ for r_ in range(1, n // 2 + 1) if (n // 2) % r_ == 0),
              key=lambda r_: abs(n / (2.0 * r_) - half))
    A = n / (2.0 * res)
    tab = os.path.join(kdir, "_cli.fits")
    cli_checks = []
    for thr in a.kerrz_threads:
        cmd = [a.kerrzcli, "image", "--spin", repr(a.spin), "--incl", repr(a.incl),
               "--alpha", repr(A), "--beta", repr(A), "--resolution", str(res),
               "--nthreads", str(thr), "--map", "redshift,radius,status,flux",
               "--thin-disc", "rin:%r,rout:%r" % (rin, a.rout), "--no-false-image",
               "--save", tab, "-o", os.path.join(kdir, "_cli.pgm")]
        p, wall, usr, sy, rss = timed(cmd, stdin=subprocess.DEVNULL)
        own = [l for l in p.stdout.splitlines() + p.stderr.splitlines()
               if "elapsed" in l]
        info["timings"].append({
            "what": "kerrzcli image (its own renderer), %d x %d pixels on "
                    "alpha, beta in linspace(-%g, %g, %d)" % (n, n, A, A, n),
            "command": " ".join(cmd), "npix": n, "threads": thr,
            "process_wall_s": wall, "process_user_s": usr, "process_sys_s": sy,
            "maxrss_children_so_far_MB": rss, "kerrz_reported": own[-1].split("elapsed:")[-1].strip()
            if own else None})
    t, kv = read_kerrz_table(tab)
    side = int(round(math.sqrt(len(t))))
    assert side == n, (side, n)
    # table rows run with beta ascending, alpha fastest: flip to row 0 = top
    cg = t["redshift"].reshape(n, n)[::-1].astype(np.float64)
    cst = t["status"].reshape(n, n)[::-1]
    cr = t["radius"].reshape(n, n)[::-1].astype(np.float64)
    cal = t["ax_alpha"].reshape(n, n)[0].astype(np.float64)
    cbe = t["ax_beta"].reshape(n, n)[::-1, 0].astype(np.float64)
    disc = cst == 4     # kerrzcli status codes: 2 horizon, 3 infinity, 4 disc
    cg[~disc] = np.nan
    cr[~disc] = np.nan
    np.save(os.path.join(kdir, "cli_g.npy"), cg)
    np.save(os.path.join(kdir, "cli_alpha.npy"), cal)
    np.save(os.path.join(kdir, "cli_beta.npy"), cbe)
    # re-trace the CLI's grid with the API path to show they are the same
    if a.kerrz_check:
        cdir = os.path.join(kdir, "_check")
        os.makedirs(cdir, exist_ok=True)
        np.save(os.path.join(cdir, "_alpha.npy"), cal)
        np.save(os.path.join(cdir, "_beta.npy"), cbe)
        cmd2 = [kpy, os.path.abspath(__file__), "--_kerrz-worker",
                          "--spin", repr(a.spin), "--incl", repr(a.incl), "--rout",
                          repr(a.rout), "--rin", repr(rin), "--npix", str(n),
                          "--half-width", repr(half), "--kerrz-robs",
                          repr(a.kerrz_robs), "--out", cdir]
        subprocess.run(cmd2, check=True)
        ag = np.load(os.path.join(cdir, "_g.npy"))
        for f in os.listdir(cdir):
            os.remove(os.path.join(cdir, f))
        os.rmdir(cdir)
        both = disc & np.isfinite(ag)
        cli_checks = {
            "grid": "kerrzcli's own grid", "cli_disc_pixels": int(disc.sum()),
            "api_disc_pixels": int(np.isfinite(ag).sum()),
            "mask_mismatch_pixels": int((disc != np.isfinite(ag)).sum()),
            "max_abs_dg_api_vs_cli": float(np.abs(ag[both] - cg[both]).max())
            if both.any() else None,
            "note": "kerrzcli stores float32, so ~6e-8 is rounding"}
    info["cli_vs_api_check"] = cli_checks
    for f in ("_g.npy", "_r.npy", "_time.json", "_alpha.npy", "_beta.npy",
              "_status.npy", "_cli.fits", "_cli.pgm"):
        os.remove(os.path.join(kdir, f))

    ipt = g ** 4 * pt_flux(r, a.spin) / math.pi
    save_maps(kdir, g=g, r_emit=r, I_pt=ipt, alpha=alpha, beta=beta)
    info.update({
        "image_plane": image_plane_json(n, half),
        "observer": {
            "distance": "infinity in effect: conserved quantities are set from "
                        "(alpha, beta) exactly (lambda = -alpha sin i, eta = "
                        "beta^2 + cos^2 i (alpha^2 - a^2)); the ray starts at "
                        "r = %g M, theta = i, and g is measured by a static "
                        "observer there (factor sqrt(1-2/r) = 1 - %.0e)"
                        % (a.kerrz_robs, 1.0 / a.kerrz_robs),
            "r_obs_M": a.kerrz_robs, "inclination_deg": a.incl,
            "inclination_definition": "Boyer-Lindquist theta of the observer, "
                                      "from the +z spin axis"},
        "matching_pinhole": dict(pinhole_json(n, half, a.gyoto_distance, a.incl),
                                 note="a pinhole camera that reproduces this grid "
                                      "(the same camera as Gyoto's run)"),
        "disc": {"rin_M": rin, "rin_is": "prograde ISCO", "rout_M": a.rout,
                 "spin": a.spin,
                 "velocity": "kerrz circularOrbitVelocity (prograde Keplerian "
                             "circular geodesic, +phi for a > 0)",
                 "which_image": "first crossing of the equatorial plane only "
                                "(trace_to_angle(pi/2)); equals kerrzcli "
                                "--no-false-image. NB kerrzcli --thin-disc "
                                "WITHOUT rin: extends inside the ISCO in 0.4.1, "
                                "so rin is always given"},
        "g_definition": "g = nu_obs / nu_emit = (k.u)_obs / (k.u)_emit "
                        "(kerrz 'redshift' / energyshift; 1+z = 1/g)",
        "I_pt_definition": "g^4 F(r)/pi with F the Page-Thorne flux (M = Mdot = 1), "
                           "computed by disk.py from kerrz's g and r (kerrz's own "
                           "'flux' map is g^3 x emissivity, default emissivity "
                           "r^-3, so it is not used)",
        "files": {"g": "g.npy", "r_emit": "r_emit.npy", "I_pt": "I_pt.npy",
                  "alpha_per_col": "alpha.npy", "beta_per_row": "beta.npy",
                  "cli_g_on_cli_grid": "cli_g.npy (+ cli_alpha.npy, cli_beta.npy)"},
    })
    json.dump(info, open(os.path.join(kdir, "conventions.json"), "w"), indent=1)
    map_png(os.path.join(kdir, "g.png"), g, scale=max(1, 512 // n))
    return g, info


# ------------------------------------------------------------------ Gyoto --

GYOTO_XML = """<?xml version="1.0" encoding="UTF-8" standalone="no"?>
<Scenery>
  <Metric kind="KerrBL"><Spin>{spin!r}</Spin></Metric>
  <Screen>
    <Position> 0. {dist!r} {theta!r} 0. </Position>
    <Time unit="geometrical_time"> 0. </Time>
    <FieldOfView> {fov!r} </FieldOfView>
    <AngleKind>Rectilinear</AngleKind>
    <Resolution> {npix} </Resolution>
  </Screen>
  <Astrobj kind="PageThorneDisk">
    <InnerRadius> {rin!r} </InnerRadius>
    <OuterRadius> {rout!r} </OuterRadius>
    <RMax> {rmax!r} </RMax>
  </Astrobj>
  <Quantities> Redshift User4 ImpactCoords </Quantities>
  <MinimumTime> {tmin!r} </MinimumTime>
  <RelTol> {tol!r} </RelTol>
  <AbsTol> {tol!r} </AbsTol>
</Scenery>
"""


def read_fits_images(path):
    """Minimal FITS reader for Gyoto's output: list of (header, array)."""
    buf = open(path, "rb").read()
    off, out = 0, []
    while off + 2880 <= len(buf):
        cards = []
        while True:
            blk = buf[off:off + 2880]
            off += 2880
            cards += [blk[k:k + 80].decode("ascii", "replace") for k in range(0, 2880, 80)]
            if any(c[:8].strip() == "END" for c in cards[-36:]):
                break
        kv = {}
        for c in cards:
            if c[8:10] == "= ":
                kv[c[:8].strip()] = c[10:].split("/")[0].strip().strip("'").strip()
        nax = int(kv.get("NAXIS", 0))
        shape = [int(kv["NAXIS%d" % k]) for k in range(1, nax + 1)][::-1]
        cnt = int(np.prod(shape)) if nax else 0
        bp = int(kv["BITPIX"])
        dt = {-64: ">f8", -32: ">f4", 8: ">u1", 16: ">i2", 32: ">i4", 64: ">i8"}[bp]
        nb = cnt * abs(bp) // 8
        arr = np.frombuffer(buf[off:off + nb], dtype=dt).reshape(shape).astype(np.float64) \
            if cnt else None
        off += (nb + 2879) // 2880 * 2880
        out.append((kv, arr))
    return out


def gyoto_exact_alpha_beta(xml, spin, n):
    """Exact (alpha, beta) of every Gyoto pixel from the photon's initial
    4-momentum (Gyoto's Screen::getRayCoord), in the common orientation."""
    import gyoto.core  # noqa: F401
    import gyoto.std  # noqa: F401
    sc = gyoto.core.Factory(xml).scenery()
    scr = sc.screen()
    al = np.zeros((n, n))
    be = np.zeros((n, n))
    c = np.zeros(8)
    for j in range(1, n + 1):
        for i in range(1, n + 1):
            scr.getRayCoord(i, j, c)
            r, th = c[1], c[2]
            gtt, gtp, gpp, sig = kerr_bl(r, th, spin)
            pt = gtt * c[4] + gtp * c[7]
            pp = gtp * c[4] + gpp * c[7]
            pth = sig * c[6]
            E = -pt
            al[j - 1, i - 1] = -(pp / E) / math.sin(th)
            be[j - 1, i - 1] = pth / E
    return al[::-1].copy(), be[::-1].copy(), float(c[4] * math.sqrt(-kerr_bl(c[1], c[2], spin)[0]))


def gyoto_crossings(xml, n, pixels):
    """Replay Gyoto's own photons (Scenery::clonePhoton: same metric, disc,
    tolerances) for the given FITS-layout pixels [(j-1, i-1)] and count the
    equatorial-plane crossings up to where Photon::hit stops. 1 means the
    disc hit is the first crossing (first image)."""
    import gyoto.core  # noqa: F401
    import gyoto.std  # noqa: F401
    sc = gyoto.core.Factory(xml).scenery()
    scr = sc.screen()
    c = np.zeros(8)
    out = {}
    for (jj, ii) in pixels:
        scr.getRayCoord(int(ii) + 1, int(jj) + 1, c)
        ph = sc.clonePhoton()
        ph.setInitCoord(c, -1)
        ph.hit()
        m = ph.get_nelements()
        ts = np.zeros(m)
        ph.get_t(ts)
        q = [np.zeros(m) for _ in range(7)]
        ph.getCoord(ts, *q)
        sg = np.sign(q[1] - math.pi / 2)
        out[(int(jj), int(ii))] = int((sg[1:] != sg[:-1]).sum())
    return out


def run_gyoto(a, out, rin):
    gdir = os.path.join(out, "gyoto")
    os.makedirs(gdir, exist_ok=True)
    n, half, dist = a.npix, a.half_width, a.gyoto_distance
    tan_half = half / dist
    xml = os.path.join(gdir, "scenery.xml")
    with open(xml, "w") as f:
        f.write(GYOTO_XML.format(spin=float(a.spin), dist=float(dist),
                                 theta=math.radians(a.incl), fov=2 * math.atan(tan_half),
                                 npix=n, rin=float(rin), rout=float(a.rout),
                                 rmax=float(max(3 * a.rout, 50.0)),
                                 tmin=float(-(2 * dist + 1e4)), tol=float(a.gyoto_tol)))
    fits = os.path.join(gdir, "_gyoto.fits")
    back = os.path.join(gdir, "scenery_full.xml")
    info = {"peer": "gyoto", "machine": machine(), "timings": []}
    ver = subprocess.run([a.gyoto, "--version"], capture_output=True, text=True)
    info["version"] = ver.stdout.strip().splitlines()[0] if ver.stdout else "?"
    cmd = [a.gyoto, "-P0", "-T%d" % a.gyoto_threads, "--xmlwrite=" + back, xml, "!" + fits]
    p, wall, usr, sy, rss = timed(cmd)
    own = [l for l in (p.stdout + p.stderr).splitlines() if "Raytraced" in l]
    info["timings"].append({
        "what": "gyoto CLI, KerrBL, adaptive RKF-type integrator, one photon per pixel",
        "command": " ".join(cmd), "npix": n, "threads": a.gyoto_threads,
        "process_wall_s": wall, "process_user_s": usr, "process_sys_s": sy,
        "maxrss_children_so_far_MB": rss, "gyoto_reported": own[-1].strip() if own else None})

    hdus = read_fits_images(fits)
    kv0, cube = hdus[0]
    quants = [kv0.get("QUANT_%d" % k, "") for k in range(1, cube.shape[0] + 1)]
    red = cube[quants.index("Redshift")]
    u4 = cube[quants.index("User4")]
    ic = [h for h in hdus if h[1] is not None and h[1].ndim == 3 and h[1].shape[-1] == 16][0][1]
    # FITS axis 1 = Gyoto column i (alpha increasing), axis 2 = row j (beta
    # increasing): numpy [j-1, i-1]; flip rows to put beta = +L on top.
    hit = ic[..., 0] < 1e300                  # object coords are DBL_MAX if no hit
    top_face = ic[..., 14] < 0                # photon dtheta/dt < 0: leaves the
    first = hit & top_face & (red > 0)        # upper face towards the observer
    # Higher orders that hit the upper face again (n = 2: two crossings
    # before the hit) live in a thin ring at the critical curve, which for
    # any spin lies within b = sqrt(alpha^2 + beta^2) < 7 M: replay Gyoto's
    # photons for the upper-face hits with b < B_ORDER_CHECK and drop those
    # with more than one crossing.
    alpha, beta = grid(n, half)
    bb = alpha[None, :] ** 2 + beta[::-1][:, None] ** 2     # FITS layout
    order = {"checked": False}
    if a.gyoto_order_check:
        try:
            cand = np.argwhere(first & (bb < B_ORDER_CHECK ** 2))
            t0 = time.perf_counter()
            nc = gyoto_crossings(xml, n, cand)
            higher = [k for k, v in nc.items() if v >= 2]
            for (jj, ii) in higher:
                first[jj, ii] = False
            order = {"checked": True, "b_max_M": B_ORDER_CHECK,
                     "pixels_replayed": int(len(cand)),
                     "higher_order_removed": len(higher),
                     "crossing_counts": {str(v): sum(1 for x in nc.values() if x == v)
                                         for v in sorted(set(nc.values()))},
                     "replay_wall_s": time.perf_counter() - t0}
        except ImportError as e:
            order = {"checked": False, "skipped": "gyoto python module: %s" % e}
    g = np.where(first, red, np.nan)[::-1].copy()
    ipt = np.where(first, u4, np.nan)[::-1].copy()
    r = np.where(first, ic[..., 1], np.nan)[::-1].copy()
    n_lower = int((hit & ~top_face).sum())
    if a.keep_fits:
        os.replace(fits, os.path.join(gdir, "gyoto_raw.fits"))
    else:
        os.remove(fits)

    ex = {}
    if a.gyoto_exact:
        try:
            al, be, eloc = gyoto_exact_alpha_beta(xml, a.spin, n)
            np.save(os.path.join(gdir, "alpha_exact.npy"), al)
            np.save(os.path.join(gdir, "beta_exact.npy"), be)
            ex = {"max_abs_alpha_exact_minus_nominal_M":
                  float(np.abs(al - alpha[None, :]).max()),
                  "max_abs_beta_exact_minus_nominal_M":
                  float(np.abs(be - beta[:, None]).max()),
                  "max_rel_alpha": float(np.max(np.abs(al - alpha[None, :]) /
                                                np.abs(alpha[None, :]))),
                  "photon_energy_static_observer_last_pixel": eloc}
        except ImportError as e:
            ex = {"skipped": "gyoto python module not importable: %s" % e}
    save_maps(gdir, g=g, I_pt=ipt, r_emit=r, alpha=alpha, beta=beta)
    info.update({
        "image_plane": image_plane_json(n, half),
        "pixel_mapping_exact_check": ex,
        "higher_order_filter": order,
        "observer": dict(pinhole_json(n, half, dist, a.incl), **{
            "gyoto_screen": "Position = (t=0, r=D, theta=i, phi=0) -> PALN = pi, "
                            "Inclination = pi - i, Argument = -pi/2 (Gyoto's "
                            "Screen 'Inclination' is pi - theta_obs); AngleKind "
                            "Rectilinear; ObserverKind ObserverAtInfinity (static "
                            "frame at r = D); FieldOfView = 2 atan(L/D) rad",
            "gyoto_pixel": "Gyoto pixel (i, j), 1-based: x_gyoto = -delta (i - "
                           "(N+1)/2), y = delta (j - (N+1)/2), delta = 2 tan(fov/2)/N; "
                           "with PALN = pi, alpha = +D delta (i - (N+1)/2), beta = "
                           "+D delta (j - (N+1)/2); so common col = i - 1 and common "
                           "row = N - j; FITS row 1 (j = 1) is the bottom (beta = -L)"}),
        "disc": {"rin_M": rin, "rin_is": "prograde ISCO", "rout_M": a.rout,
                 "spin": a.spin, "astrobj": "PageThorneDisk, CoRotating (gas moves "
                 "in +phi: prograde for a > 0), Keplerian circular geodesics, "
                 "optically thick",
                 "which_image": "Gyoto ray-traces all orders; kept: pixels whose "
                                "hit is on the upper face (photon dtheta/dt < 0 at "
                                "the hit, from ImpactCoords); %d lower-face "
                                "(secondary image) pixels set to NaN; upper-face "
                                "hits after >1 equatorial crossing (n = 2 ring "
                                "at the critical curve) removed by replaying "
                                "Gyoto's photons, see higher_order_filter"
                                % n_lower},
        "g_definition": "Gyoto 'Redshift' = nu_obs/nu_emit = 1/(-k.u_emit) with k "
                        "normalised to unit energy in the static frame at r = D: "
                        "so g_gyoto = g_infinity / sqrt(1 - 2/D) (= 1 + %.1e "
                        "relative here); 1+z = 1/g" % (1.0 / dist),
        "I_pt_definition": "Gyoto 'User4' (PageThorneDisk bolometric intensity) = "
                           "g^4 F(r)/pi, F Page-Thorne flux, M = Mdot = 1",
        "integrator": {"RelTol": a.gyoto_tol, "AbsTol": a.gyoto_tol,
                       "full_scenery_written_back": "scenery_full.xml"},
        "files": {"g": "g.npy", "r_emit": "r_emit.npy", "I_pt": "I_pt.npy",
                  "alpha_per_col": "alpha.npy", "beta_per_row": "beta.npy",
                  "alpha_beta_exact_per_pixel": "alpha_exact.npy, beta_exact.npy",
                  "scenery": "scenery.xml"},
    })
    json.dump(info, open(os.path.join(gdir, "conventions.json"), "w"), indent=1)
    map_png(os.path.join(gdir, "g.png"), g, scale=max(1, 512 // n))
    return g, info


# ------------------------------------------------------------------- main --

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spin", type=float, default=0.9)
    ap.add_argument("--incl", type=float, default=80.0, help="degrees from +z")
    ap.add_argument("--rout", type=float, default=20.0, help="outer radius, M")
    ap.add_argument("--rin", type=float, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--npix", type=int, default=128)
    ap.add_argument("--half-width", type=float, default=25.0,
                    help="half-width L of the image plane, M (alpha, beta in [-L, L])")
    ap.add_argument("--out", required=True)
    ap.add_argument("--peers", default="kerrz,gyoto")
    ap.add_argument("--kerrz-python", default=DEFAULT_KERRZ_PY)
    ap.add_argument("--kerrzcli", default=None,
                    help="default: kerrzcli next to --kerrz-python")
    ap.add_argument("--kerrz-threads", default="1,2",
                    help="thread counts for the kerrzcli timing runs")
    ap.add_argument("--kerrz-robs", type=float, default=1e7)
    ap.add_argument("--no-kerrz-check", dest="kerrz_check", action="store_false")
    ap.add_argument("--gyoto", default="gyoto")
    ap.add_argument("--gyoto-threads", type=int, default=1)
    ap.add_argument("--gyoto-distance", type=float, default=1e6, help="M")
    ap.add_argument("--gyoto-tol", type=float, default=1e-12)
    ap.add_argument("--keep-fits", action="store_true",
                    help="keep Gyoto's raw FITS as OUT/gyoto/gyoto_raw.fits")
    ap.add_argument("--no-gyoto-exact", dest="gyoto_exact", action="store_false")
    ap.add_argument("--no-gyoto-order-check", dest="gyoto_order_check",
                    action="store_false")
    ap.add_argument("--_kerrz-worker", dest="worker", action="store_true",
                    help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.worker:
        return kerrz_worker(a)
    if not 0 <= a.spin < 1:
        raise SystemExit("only 0 <= a < 1 (for a < 0 render |a| and mirror alpha)")
    a.kerrz_threads = [int(t) for t in a.kerrz_threads.split(",") if t]
    if a.kerrzcli is None:
        a.kerrzcli = os.path.join(os.path.dirname(a.kerrz_python), "kerrzcli")
    rin = isco(a.spin)
    os.makedirs(a.out, exist_ok=True)
    peers = [p for p in a.peers.split(",") if p]
    if "kerrz" in peers:
        info = run_kerrz(a, a.out, rin)[1]
        for t in info["timings"]:
            print("kerrz %-60.60s wall %.3f s user %.3f s" % (t["what"], t["process_wall_s"],
                                                          t["process_user_s"]))
        print("kerrz API vs CLI:", info["cli_vs_api_check"])
    if "gyoto" in peers:
        info = run_gyoto(a, a.out, rin)[1]
        for t in info["timings"]:
            print("gyoto -T%d wall %.3f s user %.3f s (%s)" % (
                t["threads"], t["process_wall_s"], t["process_user_s"], t["gyoto_reported"]))
        print("gyoto pixel mapping:", info["pixel_mapping_exact_check"])
    fk, fg = (os.path.join(a.out, p, "g.npy") for p in ("kerrz", "gyoto"))
    if os.path.exists(fk) and os.path.exists(fg):
        # compare whatever both peers left in OUT (they may come from two runs)
        gk, gg = np.load(fk), np.load(fg)
        both = np.isfinite(gk) & np.isfinite(gg)
        d = np.abs(gk - gg)
        dn = np.where(both, gk - gg, np.nan)
        cmp = {"spin": a.spin, "incl_deg": a.incl, "rout": a.rout, "npix": a.npix,
               "half_width": a.half_width, "rin": rin,
               "pixels_kerrz": int(np.isfinite(gk).sum()),
               "pixels_gyoto": int(np.isfinite(gg).sum()),
               "pixels_both": int(both.sum()),
               "pixels_only_kerrz": int((np.isfinite(gk) & ~np.isfinite(gg)).sum()),
               "pixels_only_gyoto": int((~np.isfinite(gk) & np.isfinite(gg)).sum()),
               "max_abs_dg": float(d[both].max()), "median_abs_dg": float(np.median(d[both])),
               "p99_abs_dg": float(np.percentile(d[both], 99)),
               "max_rel_dg": float((d[both] / gk[both]).max()),
               "median_signed_rel_dg_gyoto_over_kerrz_minus_1":
               float(np.median(gg[both] / gk[both] - 1)),
               "note": "dg = g_kerrz - g_gyoto; g_gyoto carries the static-observer "
                       "factor 1/sqrt(1-2/D) - 1 = %.1e" % (1 / math.sqrt(1 - 2 / a.gyoto_distance) - 1)}
        ik, ig = np.load(os.path.join(a.out, "kerrz", "I_pt.npy")), \
            np.load(os.path.join(a.out, "gyoto", "I_pt.npy"))
        rel = np.abs(ik[both] / ig[both] - 1)
        rk, rg = np.load(os.path.join(a.out, "kerrz", "r_emit.npy")), \
            np.load(os.path.join(a.out, "gyoto", "r_emit.npy"))
        cmp["I_pt_max_rel_diff"] = float(rel.max())
        cmp["I_pt_median_rel_diff"] = float(np.median(rel))
        away = rk[both] > 1.05 * rin     # F -> 0 at the ISCO: relative diffs blow up
        cmp["I_pt_max_rel_diff_r_gt_1.05rin"] = float(rel[away].max())
        cmp["mismatch_pixels"] = [
            {"row": int(r_), "col": int(c_), "g_kerrz": _num(gk[r_, c_]),
             "g_gyoto": _num(gg[r_, c_]), "r_kerrz": _num(rk[r_, c_]),
             "r_gyoto": _num(rg[r_, c_])}
            for r_, c_ in np.argwhere(np.isfinite(gk) != np.isfinite(gg))[:50]]
        cmp["r_emit_max_abs_diff"] = float(np.abs(rk - rg)[both].max())
        cmp["r_emit_median_abs_diff"] = float(np.median(np.abs(rk - rg)[both]))
        worst = np.unravel_index(np.nanargmax(np.where(both, d, np.nan)), d.shape)
        cmp["worst_pixel_row_col"] = [int(worst[0]), int(worst[1])]
        json.dump(cmp, open(os.path.join(a.out, "compare.json"), "w"), indent=1)
        map_png(os.path.join(a.out, "dg.png"), dn, diverging=True,
                scale=max(1, 512 // a.npix))
        print(json.dumps(cmp, indent=1))


if __name__ == "__main__":
    main()
