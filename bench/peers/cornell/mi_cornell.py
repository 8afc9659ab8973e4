#!/usr/bin/env python3
"""nullpath's Cornell box (scenes/cornell-box.toml) as a Mitsuba 3 scene, and a one-shot renderer.

The Mitsuba scene is built from the TOML file itself (the subset it uses: `rectangle` and `box`
shapes, `transform` with scale/rotate/translate, `diffuse` materials, `emission` radiance), so the
two renderers read the same numbers. Mapping (see README.md, "Equivalence"):

* rectangle corner/edge_u/edge_v -> `rectangle` ([-1, 1]^2, normal +z) with to_world columns
  (edge_u/2, edge_v/2, unit(edge_u x edge_v), centre): same parallelogram, same normal;
* box min/max + transform T.R.S -> `cube` ([-1, 1]^3) with to_world T.R.S.translate(c).scale(h);
  rotations right-handed about the given axis (as nullpath; checked against the published corners);
* diffuse -> `twosided` `diffuse` (nullpath's diffuse reflects on both sides; Mitsuba's is one-sided);
* emission -> `area` emitter (one-sided, on the normal's side, as nullpath's default two_sided=false);
* camera -> `perspective`, fov_axis y, look_at(position, look_at, up), box filter (nullpath's default
  pixel filter is a box of radius 0.5: each pixel averages its own square);
* max_depth M (nullpath: surface interactions) -> Mitsuba `path` max_depth M + 1 (path vertices incl.
  the camera's ray end: 1 = emitters seen directly); Russian roulette: nullpath starts at bounce 2
  with survival min(1, max beta) -> Mitsuba rr_depth 2 (survival min(0.95, max beta); the 0.95 cap
  never binds here: every albedo is <= 0.78).

Spectral variants (scalar_spectral, llvm_ad_spectral) take the same dict: an `rgb` reflectance
becomes an SRGBReflectanceSpectrum (Jakob & Hanika 2019 sigmoid polynomial from Mitsuba's table),
and an `rgb` emitter radiance becomes a D65Spectrum (area.cpp reads it with texture_d65): scale =
2 max(rgb), the sigmoid spectrum of rgb / scale, times scale, times CIE D65 -- an illuminant, as
nullpath's --spectral (pbrt-v4's RGBIlluminantSpectrum). hdrfilm with pixel_format rgb integrates
the sampled wavelengths to XYZ and writes linear sRGB (Rec. 709), as nullpath's spectral film.
MI_RESULT records the emitter's radiance plugin ("emitter_radiance") to show which one was used.

Usage (worker; the harness calls it as a subprocess so that startup/JIT is part of the wall time):
  python mi_cornell.py --variant llvm_ad_rgb --spp 64 --threads 1 --sampler independent \
      --res 128 --seed 0 --out /tmp/mi.npy [--exr /tmp/mi.exr] [--xml scene.xml]
Prints one line `MI_RESULT {json}`: timings (import, load, render), actual spp, mean RGB.
"""
import argparse
import json
import math
import os
import sys
import time

T_START = time.perf_counter()

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE_TOML = os.path.normpath(os.path.join(HERE, "..", "..", "..", "scenes", "cornell-box.toml"))

SAMPLERS = ["independent", "stratified", "multijitter", "orthogonal", "ldsampler"]


# ----------------------------------------------------------------- small linear algebra (no numpy)
def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def translate(t):
    return [[1, 0, 0, t[0]], [0, 1, 0, t[1]], [0, 0, 1, t[2]], [0, 0, 0, 1]]


def scale(s):
    if isinstance(s, (int, float)):
        s = [s, s, s]
    return [[s[0], 0, 0, 0], [0, s[1], 0, 0], [0, 0, s[2], 0], [0, 0, 0, 1]]


def rotate(axis, degrees):
    """Right-handed rotation by `degrees` about `axis` (Rodrigues)."""
    n = math.sqrt(sum(x * x for x in axis))
    x, y, z = (c / n for c in axis)
    # exact multiples of 90 degrees, as nullpath
    d = degrees % 360.0
    exact = {0.0: (1.0, 0.0), 90.0: (0.0, 1.0), 180.0: (-1.0, 0.0), 270.0: (0.0, -1.0)}
    c, s = exact.get(d, (math.cos(math.radians(degrees)), math.sin(math.radians(degrees))))
    C = 1 - c
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s, 0],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s, 0],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C, 0],
            [0, 0, 0, 1]]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def object_transform(tr):
    """nullpath's transform table -> 4x4 (T . R . S)."""
    m = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]
    if not tr:
        return m
    unknown = set(tr) - {"scale", "rotate", "translate"}
    if unknown:
        raise SystemExit("unsupported transform keys %s" % unknown)
    if "scale" in tr:
        m = matmul(scale(tr["scale"]), m)
    rots = tr.get("rotate", [])
    if isinstance(rots, dict):
        rots = [rots]
    for r in rots:  # "a list is applied in order"
        m = matmul(rotate(r["axis"], r["degrees"]), m)
    if "translate" in tr:
        m = matmul(translate(tr["translate"]), m)
    return m


def rgb(v):
    return [float(v)] * 3 if isinstance(v, (int, float)) else [float(x) for x in v]


# ----------------------------------------------------------------------------- the scene (plain data)
def scene_description(toml_path=SCENE_TOML, res=None):
    """Renderer-neutral description of the TOML scene: shapes as 4x4 to_world matrices."""
    import tomllib
    with open(toml_path, "rb") as f:
        s = tomllib.load(f)
    cam = s["camera"]
    r = s.get("render", {})
    if s.get("spacetime", {}).get("type", "minkowski") != "minkowski":
        raise SystemExit("only flat space can be compared with Mitsuba")
    flt = r.get("filter", "box")
    if flt not in ("box", {"type": "box"}, {"type": "box", "radius": 0.5}):
        raise SystemExit("only nullpath's default box filter is mapped, got %r" % (flt,))
    mats = {}
    for name, m in s.get("materials", {}).items():
        if m.get("type") != "diffuse":
            raise SystemExit("material %s: only diffuse is mapped" % name)
        mats[name] = rgb(m["reflectance"])
    objects = []
    for i, o in enumerate(s["objects"]):
        sh = o["shape"]
        xf = object_transform(o.get("transform"))
        if sh["type"] == "rectangle":
            c, u, v = sh["corner"], sh["edge_u"], sh["edge_v"]
            n = cross(u, v)
            nl = math.sqrt(sum(x * x for x in n))
            n = [x / nl for x in n]
            ctr = [c[k] + 0.5 * (u[k] + v[k]) for k in range(3)]
            local = [[0.5 * u[0], 0.5 * v[0], n[0], ctr[0]],
                     [0.5 * u[1], 0.5 * v[1], n[1], ctr[1]],
                     [0.5 * u[2], 0.5 * v[2], n[2], ctr[2]],
                     [0, 0, 0, 1]]
            kind = "rectangle"
        elif sh["type"] == "box":
            lo, hi = sh["min"], sh["max"]
            local = matmul(translate([(lo[k] + hi[k]) / 2 for k in range(3)]),
                           scale([(hi[k] - lo[k]) / 2 for k in range(3)]))
            kind = "cube"
        else:
            raise SystemExit("object %d: shape %s not mapped" % (i, sh["type"]))
        mat = o.get("material")
        albedo = mats[mat] if isinstance(mat, str) else (rgb(mat["reflectance"]) if mat else [0.5] * 3)
        if isinstance(mat, dict) and mat.get("type") != "diffuse":
            raise SystemExit("object %d: only diffuse is mapped" % i)
        em = o.get("emission")
        radiance = None
        if em is not None:
            if isinstance(em, dict):
                if em.get("two_sided", False):
                    raise SystemExit("two-sided emitters are not mapped")
                radiance = rgb(em["radiance"])
            else:
                radiance = rgb(em)
        objects.append({"kind": kind, "to_world": matmul(xf, local), "albedo": albedo,
                        "radiance": radiance})
    width = res or r.get("width", 640)
    height = res or r.get("height", 480)
    return {
        "camera": {"position": cam["position"], "look_at": cam["look_at"],
                   "up": cam.get("up", [0, 1, 0]), "fov": cam.get("fov", 40)},
        "width": width, "height": height,
        "max_depth": r.get("max_depth", 8),
        "objects": objects,
    }


def mitsuba_dict(desc, spp, sampler="independent", rr_depth=2):
    import mitsuba as mi
    T = mi.ScalarTransform4f
    cam = desc["camera"]
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": desc["max_depth"] + 1, "rr_depth": rr_depth},
        "sensor": {
            "type": "perspective", "fov_axis": "y", "fov": float(cam["fov"]),
            "near_clip": 1.0, "far_clip": 1.0e5,
            "to_world": T().look_at(origin=cam["position"], target=cam["look_at"], up=cam["up"]),
            "sampler": {"type": sampler, "sample_count": spp},
            "film": {"type": "hdrfilm", "width": desc["width"], "height": desc["height"],
                     "rfilter": {"type": "box"}, "pixel_format": "rgb",
                     "component_format": "float32"},
        },
    }
    for i, o in enumerate(desc["objects"]):
        e = {"type": o["kind"], "to_world": T(o["to_world"]),
             "bsdf": {"type": "twosided",
                      "bsdf": {"type": "diffuse",
                               "reflectance": {"type": "rgb", "value": o["albedo"]}}}}
        if o["radiance"] is not None:
            e["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": o["radiance"]}}
        d["object%02d" % i] = e
    return d


def mitsuba_xml(desc, spp, sampler="independent", rr_depth=2):
    """The same scene as Mitsuba 3 XML (for the `mitsuba` command line)."""
    def m(mat):
        return " ".join("%.9g" % mat[i][j] for i in range(4) for j in range(4))

    def v(x):
        return ", ".join("%.9g" % c for c in x)
    cam = desc["camera"]
    out = ['<scene version="3.0.0">',
           '  <!-- generated by bench/peers/cornell/mi_cornell.py from scenes/cornell-box.toml -->',
           '  <integrator type="path">',
           '    <integer name="max_depth" value="%d"/>' % (desc["max_depth"] + 1),
           '    <integer name="rr_depth" value="%d"/>' % rr_depth,
           '  </integrator>',
           '  <sensor type="perspective">',
           '    <string name="fov_axis" value="y"/>',
           '    <float name="fov" value="%.9g"/>' % cam["fov"],
           '    <float name="near_clip" value="1"/>',
           '    <float name="far_clip" value="100000"/>',
           '    <transform name="to_world">',
           '      <lookat origin="%s" target="%s" up="%s"/>' % (v(cam["position"]), v(cam["look_at"]), v(cam["up"])),
           '    </transform>',
           '    <sampler type="%s"><integer name="sample_count" value="%d"/></sampler>' % (sampler, spp),
           '    <film type="hdrfilm">',
           '      <integer name="width" value="%d"/>' % desc["width"],
           '      <integer name="height" value="%d"/>' % desc["height"],
           '      <rfilter type="box"/>',
           '      <string name="pixel_format" value="rgb"/>',
           '    </film>',
           '  </sensor>']
    for o in desc["objects"]:
        out += ['  <shape type="%s">' % o["kind"],
                '    <transform name="to_world"><matrix value="%s"/></transform>' % m(o["to_world"]),
                '    <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="%s"/></bsdf></bsdf>' % v(o["albedo"])]
        if o["radiance"] is not None:
            out.append('    <emitter type="area"><rgb name="radiance" value="%s"/></emitter>' % v(o["radiance"]))
        out.append('  </shape>')
    out.append('</scene>')
    return "\n".join(out) + "\n"


# ------------------------------------------------------------------------------------------- worker
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default=SCENE_TOML)
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--res", type=int, default=None, help="square image side (default: the scene's size)")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--sampler", default="independent", choices=SAMPLERS)
    ap.add_argument("--rr-depth", type=int, default=2)
    ap.add_argument("--threads", type=int, default=0, help="0: Dr.Jit's default (all cores)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default=None, help=".npy of the float32 H x W x 3 image")
    ap.add_argument("--exr", default=None, help="also write an EXR")
    ap.add_argument("--xml", default=None, help="write the scene as Mitsuba XML and exit")
    a = ap.parse_args()

    desc = scene_description(a.scene, a.res)
    if a.xml:
        with open(a.xml, "w") as f:
            f.write(mitsuba_xml(desc, a.spp, a.sampler, a.rr_depth))
        return
    if a.variant.startswith("llvm"):
        os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
    import numpy as np
    import mitsuba as mi
    mi.set_variant(a.variant)
    mi.set_log_level(mi.LogLevel.Error)  # the samplers' "rounding to N" warnings: N is reported
    import drjit as dr
    default_threads = dr.thread_count()
    if a.threads > 0:
        dr.set_thread_count(a.threads)
    t_import = time.perf_counter()
    scene = mi.load_dict(mitsuba_dict(desc, a.spp, a.sampler, a.rr_depth))
    spp = scene.sensors()[0].sampler().sample_count()
    t_load = time.perf_counter()
    img = mi.render(scene, seed=a.seed)
    arr = np.array(img, dtype=np.float32)  # forces evaluation of the kernel
    t_render = time.perf_counter()
    used_threads = dr.thread_count()
    ems = scene.emitters()
    emitter_radiance = str(ems[0]).split("radiance = ", 1)[1].split("[", 1)[0].strip() if ems else None
    # Bitmap.write deadlocks with a pool of one thread (drjit 1.5.0): restore the pool first.
    dr.set_thread_count(default_threads)
    if a.out:
        np.save(a.out, arr)
    if a.exr:
        mi.Bitmap(arr).write(a.exr)
    print("MI_RESULT " + json.dumps({
        "renderer": "mitsuba", "variant": a.variant, "sampler": a.sampler, "spp": int(spp),
        "spp_requested": a.spp, "threads": used_threads, "seed": a.seed,
        "width": desc["width"], "height": desc["height"], "max_depth": desc["max_depth"] + 1,
        "rr_depth": a.rr_depth, "emitter_radiance": emitter_radiance,
        "import_s": t_import - T_START, "load_s": t_load - t_import, "render_s": t_render - t_load,
        "mean_rgb": [float(x) for x in arr.reshape(-1, 3).mean(0)],
    }))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
