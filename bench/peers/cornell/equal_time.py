#!/usr/bin/env python3
"""Equal-time RMSE: nullpath against Mitsuba 3 on nullpath's Cornell box (flat space).

Run with the venv's python (Mitsuba 3.9.1 + numpy), e.g.
  /work/peers-run/venv-mi/bin/python bench/peers/cornell/equal_time.py --budgets 2,8 --threads 1,2

Every render is a child process under `nice -n 19`; its wall time is the process's (start-up,
Python import, scene load and LLVM JIT included) and is reported split into start-up and render.

1. Reference ($CORNELL_RUN_DIR/ref_RES, default /work/peers-run/cornell): nullpath chunks
   (--ref-nullpath CHUNKS x SPP) and Mitsuba llvm_ad_rgb/independent chunks (--ref-mitsuba), each
   with its own seed; reused when present (missing chunks are rendered, so it can be resumed).
   The two renderers' means are averaged with weights inverse to their noise (the image-average
   squared standard error, from the spread over chunks); that noise, mse_ref, is subtracted from
   every MSE below (E|x - ref|^2 = E|x - truth|^2 + mse_ref for independent renders).
2. Sampler study (cached, samplers_RES.json): Mitsuba llvm_ad_rgb with independent, stratified,
   multijitter, orthogonal and ldsampler at --study-spp, --study-seeds seeds each; RMSE at equal spp
   (orthogonal, which takes only squares of primes, runs at the valid counts on both sides and is
   interpolated log-log). The lowest (geometric mean over the levels) is used below (or --sampler);
   --extra-sampler adds another llvm_ad_rgb sampler to the equal-time runs for information.
3. For each thread count and budget: calibration (each configuration at --calib-spp, alternating,
   twice) gives wall = startup + spp * per_spp, hence the spp that fills the budget; then --reps paired
   rounds (nullpath, Mitsuba llvm_ad_rgb, Mitsuba scalar_rgb; the order reversed every other round)
   with fresh seeds. Reported per cell: spp, wall (startup + render), RMSE (reference noise
   subtracted), and the Mitsuba / nullpath ratios of RMSE as measured, time-scaled (x sqrt(wall /
   budget): MSE taken as 1/time, for walls that missed the budget) and CPU-scaled (x sqrt(CPU /
   (budget x threads)): robust to waiting for a CPU on a shared machine). RMSE of a cell =
   sqrt(mean MSE over its rounds). A sampler that only takes coarse sample counts (orthogonal:
   squares of primes; ldsampler: 4^k) runs at the counts on both sides of the calibrated spp, and
   its MSE and wall there are interpolated between the two (log-log in spp; spp shown "lo-hi").

Results: $CORNELL_RUN_DIR/equal_time_RES.json (everything, each command line included).

--spectral: the same in spectral mode: nullpath gets `--spectral` (also: $NULLPATH_ARGS, appended to
every nullpath command), Mitsuba runs llvm_ad_spectral / scalar_spectral (reference: llvm_ad_spectral);
the reference goes to ref_RES_spectral, the study to samplers_RES_spectral.json, the results to
equal_time_RES_spectral.json. nullpath's spectral renders start by optimising its RGB -> spectrum
table (about 1.2 s, once per process, inside the render's own timer): it is measured per thread count
(1-spp spectral render minus 1-spp RGB render, median of 3) and reported as a separate ratio with
nullpath's wall less that time ("no table"). --no-study skips the sampler study (needs --sampler).
"""
import argparse
import glob
import json
import os
import platform
import sys
import time

import numpy as np

import common
import mi_cornell

MI_REF_VARIANT = "llvm_ad_rgb"
MODE = {"spectral": False, "suffix": "", "llvm": "llvm_ad_rgb", "scalar": "scalar_rgb", "nullpath_args": []}


def set_spectral(on):
    global MI_REF_VARIANT
    if on:
        MODE.update(spectral=True, suffix="_spectral", llvm="llvm_ad_spectral", scalar="scalar_spectral",
                    nullpath_args=["--spectral"])
    MI_REF_VARIANT = MODE["llvm"]


# --------------------------------------------------------------------------------------- reference
def build_reference(res, n_chunks, n_spp, m_chunks, m_spp, threads, m_sampler="independent"):
    d = os.path.join(common.RUN_DIR, "ref_%d%s" % (res, MODE["suffix"]))
    os.makedirs(d, exist_ok=True)
    meta_path = os.path.join(d, "chunks.json")
    meta = {"res": res, "nullpath_spp": n_spp, "mitsuba_spp": m_spp, "mitsuba_variant": MI_REF_VARIANT,
            "mitsuba_sampler": m_sampler, "nullpath_args": common.NULLPATH_ARGS + MODE["nullpath_args"],
            "runs": []}
    if os.path.exists(meta_path):
        with open(meta_path) as f:
            old = json.load(f)
        if (old["nullpath_spp"], old["mitsuba_spp"], old.get("mitsuba_sampler", "independent")) != (
                n_spp, m_spp, m_sampler):
            sys.exit("%s was made with other chunk sizes (%d, %d spp): use those or another "
                     "CORNELL_RUN_DIR" % (meta_path, old["nullpath_spp"], old["mitsuba_spp"]))
        meta = old
    todo = []
    for k in range(max(n_chunks, m_chunks)):  # alternate the two renderers
        if k < n_chunks:
            todo.append(("n", k, os.path.join(d, "nullpath_seed%04d.exr" % (2000 + k))))
        if k < m_chunks:
            todo.append(("m", k, os.path.join(d, "mitsuba_seed%04d.npy" % (3000 + k))))
    for kind, k, path in todo:
        if os.path.exists(path):
            continue
        if kind == "n":
            r = common.run_nullpath(n_spp, threads, 2000 + k, res, path, MODE["nullpath_args"])
        else:
            r = common.run_mitsuba(MI_REF_VARIANT, m_sampler, m_spp, threads, 3000 + k, res, path)
        meta["runs"].append({x: r[x] for x in ("renderer", "spp", "seed", "wall_s", "cpu_s", "cmd")})
        print("  reference chunk %s %d: %.1f s wall, %.1f s CPU" % (r["renderer"], k, r["wall_s"], r["cpu_s"]),
              flush=True)
        with open(meta_path, "w") as f:
            json.dump(meta, f, indent=1)
    with open(meta_path, "w") as f:
        json.dump(meta, f, indent=1)

    def mean_se(files):
        s = np.stack([common.load_image(p) for p in files])
        return s.mean(0), s.std(0, ddof=1) / np.sqrt(len(s)), len(s)

    n_files = sorted(glob.glob(os.path.join(d, "nullpath_seed*.exr")))[:n_chunks]
    m_files = sorted(glob.glob(os.path.join(d, "mitsuba_seed*.npy")))[:m_chunks]
    mn, sn, kn = mean_se(n_files)
    mm, sm, km = mean_se(m_files)
    vn, vm = float((sn ** 2).mean()), float((sm ** 2).mean())
    wn = (1 / vn) / (1 / vn + 1 / vm)
    ref = wn * mn + (1 - wn) * mm
    se = np.sqrt(wn ** 2 * sn ** 2 + (1 - wn) ** 2 * sm ** 2)
    np.save(os.path.join(d, "ref.npy"), ref)
    np.save(os.path.join(d, "nullpath_mean.npy"), mn)
    np.save(os.path.join(d, "mitsuba_mean.npy"), mm)
    info = {
        "nullpath": {"chunks": kn, "spp_each": n_spp, "mse": vn, "mean_rgb": mn.reshape(-1, 3).mean(0).tolist()},
        "mitsuba": {"chunks": km, "spp_each": m_spp, "variant": MI_REF_VARIANT, "sampler": m_sampler, "mse": vm,
                    "mean_rgb": mm.reshape(-1, 3).mean(0).tolist()},
        "weight_nullpath": wn, "mse_ref": float((se ** 2).mean()),
        "mean_rgb": ref.reshape(-1, 3).mean(0).tolist(),
        "cpu_s_total": float(sum(r["cpu_s"] for r in meta["runs"])),
    }
    with open(os.path.join(d, "ref.json"), "w") as f:
        json.dump(info, f, indent=1)
    print("reference: nullpath %d x %d spp (noise rmse %.2e), mitsuba %d x %d spp (%.2e), weight of "
          "nullpath %.2f, combined noise rmse %.2e; mean RGB %s" % (
              kn, n_spp, vn ** 0.5, km, m_spp, vm ** 0.5, wn, info["mse_ref"] ** 0.5,
              np.round(info["mean_rgb"], 5).tolist()), flush=True)
    return {"ref": ref, "nullpath": (mn, vn), "mitsuba": (mm, vm), "info": info, "dir": d}


def errors(img, R):
    """MSE against the combined reference (its noise subtracted) and against each renderer's own."""
    out = {"mse_raw": float(np.mean((img - R["ref"]) ** 2))}
    out["mse"] = out["mse_raw"] - R["info"]["mse_ref"]
    for k in ("nullpath", "mitsuba"):
        m, v = R[k]
        out["mse_vs_" + k] = float(np.mean((img - m) ** 2)) - v
    return out


# ------------------------------------------------------------------------------------ sampler study
def sampler_study(R, res, spps, seeds, threads, force=False):
    path = os.path.join(common.RUN_DIR, "samplers_%d%s.json" % (res, MODE["suffix"]))
    if os.path.exists(path) and not force:
        with open(path) as f:
            st = json.load(f)
        if st["spps"] == spps and st["seeds"] == seeds and st.get("version") == 2:
            return st
    d = os.path.join(common.RUN_DIR, "study" + MODE["suffix"])
    os.makedirs(d, exist_ok=True)
    rows = []

    def counts(sampler, spp):
        # a sampler that does not take `spp` (orthogonal: prime squares) runs at the valid counts
        # on both sides of it; its MSE at `spp` is interpolated log-log between the two
        if sampler in ("independent", "multijitter") or valid_spp(sampler, spp) == spp:
            return [spp]
        return list(bracket_spp(sampler, spp))

    for spp in spps:
        for s in range(seeds):
            for sampler in mi_cornell.SAMPLERS:
                for cnt in counts(sampler, spp):
                    seed = 4000 + 100 * s + cnt
                    r = common.run_mitsuba(MODE["llvm"], sampler, cnt, threads, seed, res,
                                           os.path.join(d, "m_%s_%d_%d.npy" % (sampler, cnt, s)))
                    e = errors(common.load_image(r), R)
                    rows.append({"sampler": sampler, "level": spp, "spp_requested": cnt, "spp": r["spp"],
                                 "seed": seed, "wall_s": r["wall_s"], "render_s": r["render_s"],
                                 "cpu_s": r["cpu_s"], **e})
        # nullpath at the same spp, for information
        for s in range(seeds):
            seed = 4000 + 100 * s + spp
            r = common.run_nullpath(spp, threads, seed, res, os.path.join(d, "n_%d_%d.exr" % (spp, s)),
                                    MODE["nullpath_args"])
            e = errors(common.load_image(r), R)
            rows.append({"sampler": "nullpath-sobol", "level": spp, "spp_requested": spp, "spp": r["spp"],
                         "seed": seed, "wall_s": r["wall_s"], "render_s": r["render_s"], "cpu_s": r["cpu_s"], **e})
        print("  sampler study: %d spp done" % spp, flush=True)
    summary = {}
    for name in mi_cornell.SAMPLERS + ["nullpath-sobol"]:
        summary[name] = {}
        for spp in spps:
            rr = [x for x in rows if x["sampler"] == name and x["level"] == spp]
            acts = sorted({x["spp"] for x in rr})
            mse = {c: float(np.mean([x["mse"] for x in rr if x["spp"] == c])) for c in acts}
            per = {c: float(np.median([x["render_s"] for x in rr if x["spp"] == c])) / c for c in acts}
            if len(acts) == 1:
                m_at, t = mse[acts[0]], None
            else:
                c0, c1 = acts
                t = float(np.log(spp / c0) / np.log(c1 / c0))
                m_at = float(np.exp((1 - t) * np.log(max(mse[c0], 1e-30)) + t * np.log(max(mse[c1], 1e-30))))
            summary[name][str(spp)] = {"spp": acts, "rmse_each_count": {str(c): max(mse[c], 0) ** 0.5 for c in acts},
                                       "rmse_at_requested_spp": max(m_at, 0) ** 0.5, "interpolation_t": t,
                                       "render_ms_per_spp": 1e3 * float(np.mean(list(per.values())))}
    # rank by the geometric mean over the spp levels of the RMSE at equal spp
    score = {n: float(np.exp(np.mean([np.log(summary[n][str(s)]["rmse_at_requested_spp"]) for s in spps])))
             for n in mi_cornell.SAMPLERS}
    best = min(score, key=score.get)
    st = {"version": 2, "spps": spps, "seeds": seeds, "threads": threads, "rows": rows, "summary": summary,
          "score": score, "best": best}
    with open(path, "w") as f:
        json.dump(st, f, indent=1)
    return st


def print_study(st):
    spps = st["spps"]
    print("RMSE at equal spp (Mitsuba %s, %d threads; mean MSE of %d seeds; [a-b]: interpolated "
          "log-log between the valid counts a and b) and render ms per spp" % (MODE["llvm"], st["threads"], st["seeds"]))
    print("| sampler | " + " | ".join("%d spp" % s for s in spps) + " | geometric mean | ms/spp |")
    print("|---" * (len(spps) + 3) + "|")
    for n in mi_cornell.SAMPLERS + ["nullpath-sobol"]:
        cells = []
        for s in spps:
            c = st["summary"][n][str(s)]
            tag = "" if c["spp"] == [s] else " [%s]" % "-".join(str(x) for x in c["spp"])
            cells.append("%.5f%s" % (c["rmse_at_requested_spp"], tag))
        sc = st["score"].get(n)
        ms = np.mean([st["summary"][n][str(s)]["render_ms_per_spp"] for s in spps[-1:]])
        print("| %s | %s | %s | %.2f |" % (n, " | ".join(cells), "%.5f" % sc if sc else "-", ms))
    print("best Mitsuba sampler at equal spp: %s" % st["best"], flush=True)


# ------------------------------------------------------------------------------------ equal time
def valid_counts(sampler):
    """Sample counts a coarse Mitsuba sampler keeps unchanged (checked against Mitsuba 3.9.1)."""
    if sampler == "stratified":
        return [k * k for k in range(1, 400)]
    if sampler == "ldsampler":
        return [4 ** k for k in range(1, 10)]
    if sampler == "orthogonal":
        primes = [p for p in range(2, 400) if all(p % q for q in range(2, int(p ** 0.5) + 1))]
        return [p * p for p in primes]
    raise ValueError(sampler)


def valid_spp(sampler, target):
    """The count nearest to target (in ratio) that the sampler keeps (>= 1)."""
    target = max(1.0, target)
    if sampler in ("independent", "multijitter"):
        return max(1, int(round(target)))
    return min(valid_counts(sampler), key=lambda c: abs(np.log(c / target)))


def bracket_spp(sampler, target):
    """The sampler's valid counts just below (or at) and just above target."""
    cands = valid_counts(sampler)
    lo = max([c for c in cands[:-1] if c <= target] or [cands[0]])
    hi = min(c for c in cands if c > lo)
    return lo, hi


def run_config(cfg, spp, threads, seed, res, tag):
    d = os.path.join(common.RUN_DIR, "runs" + MODE["suffix"])
    os.makedirs(d, exist_ok=True)
    if cfg["renderer"] == "nullpath":
        return common.run_nullpath(spp, threads, seed, res, os.path.join(d, "%s.exr" % tag), cfg.get("args", []))
    return common.run_mitsuba(cfg["variant"], cfg["sampler"], spp, threads, seed, res,
                              os.path.join(d, "%s.npy" % tag))


def calibrate(cfgs, threads, res, lo, hi):
    """wall = startup + spp * per_spp from runs at `lo` and `hi` spp (alternating, each twice)."""
    meas = {c["name"]: {lo: [], hi: []} for c in cfgs}
    for rep in range(2):
        for spp in (lo, hi):
            for c in (cfgs if rep == 0 else cfgs[::-1]):
                s = valid_spp(c.get("sampler", "independent"), spp) if c["renderer"] == "mitsuba" else spp
                r = run_config(c, s, threads, 9000 + rep, res, "calib_%s_t%d_%d" % (c["name"], threads, spp))
                meas[c["name"]][spp].append((r["spp"], r["wall_s"], r["startup_s"], r["render_s"]))
    fit = {}
    for c in cfgs:
        m = meas[c["name"]]
        s1, s2 = m[lo][0][0], m[hi][0][0]
        med = {k: [float(np.median([x[i] for x in m[k]])) for i in (1, 2, 3)] for k in (lo, hi)}
        # the slope from the renders' own timers (less noisy than the process's wall), kept at
        # least half the high run's mean per spp; the intercept from the wall of the low run
        per = max((med[hi][2] - med[lo][2]) / (s2 - s1), 0.5 * med[hi][2] / s2)
        fit[c["name"]] = {"startup_s": med[lo][0] - per * s1, "per_spp_s": per,
                          "startup_measured_s": float(np.median([x[2] for k in (lo, hi) for x in m[k]])),
                          "points": {str(k): m[k] for k in m}}
        print("  calibration %-22s threads %d: wall = %.2f s + %.2f ms/spp (process start-up outside the "
              "render: %.2f s)" % (c["name"], threads, fit[c["name"]]["startup_s"], 1e3 * per,
                                   fit[c["name"]]["startup_measured_s"]), flush=True)
    return fit


def measure_table(threads, res, n=3):
    """nullpath --spectral's one-off RGB -> spectrum table optimisation: median wall of a 1-spp
    spectral render minus that of a 1-spp RGB render (same binary, same thread count)."""
    d = os.path.join(common.RUN_DIR, "runs" + MODE["suffix"])
    os.makedirs(d, exist_ok=True)
    rgb_args = [x for x in common.NULLPATH_ARGS if x != "--spectral"]
    saved = common.NULLPATH_ARGS
    walls = {"spectral": [], "rgb": []}
    try:
        for i in range(n):
            for kind in ("spectral", "rgb"):
                common.NULLPATH_ARGS = rgb_args + (["--spectral"] if kind == "spectral" else [])
                r = common.run_nullpath(1, threads, 9500 + i, res,
                                        os.path.join(d, "table_%s_t%d.exr" % (kind, threads)))
                walls[kind].append(r["wall_s"])
    finally:
        common.NULLPATH_ARGS = saved
    t = float(np.median(walls["spectral"]) - np.median(walls["rgb"]))
    print("  nullpath spectral table (1-spp spectral - 1-spp RGB wall, %d thread(s)): %.2f s" % (threads, t),
          flush=True)
    return {"table_s": t, "walls": walls}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, default=128)
    ap.add_argument("--budgets", default="2,8", help="seconds of wall time, comma-separated")
    ap.add_argument("--threads", default="1,2")
    ap.add_argument("--reps", type=int, default=4, help="paired rounds per (threads, budget)")
    ap.add_argument("--no-scalar", action="store_true", help="leave out Mitsuba scalar_rgb")
    ap.add_argument("--sampler", default=None, help="Mitsuba sampler (default: the study's best)")
    ap.add_argument("--extra-sampler", default="multijitter",
                    help="more llvm_ad_rgb samplers for the equal-time runs, comma-separated ('' for none)")
    ap.add_argument("--ref-nullpath", default="16x2048", help="reference chunks x spp for nullpath")
    ap.add_argument("--ref-mitsuba", default="16x8192", help="reference chunks x spp for Mitsuba llvm")
    ap.add_argument("--ref-mitsuba-sampler", default="independent", help="sampler of Mitsuba's reference chunks")
    ap.add_argument("--spectral", action="store_true",
                    help="spectral mode: nullpath --spectral, Mitsuba llvm_ad_spectral / scalar_spectral")
    ap.add_argument("--no-study", action="store_true", help="skip the sampler study (use --sampler)")
    ap.add_argument("--ref-threads", type=int, default=2)
    ap.add_argument("--study-spp", default="16,64,256")
    ap.add_argument("--study-seeds", type=int, default=3)
    ap.add_argument("--calib-spp", default="4,128", help="the two spp of the calibration")
    ap.add_argument("--out", default=None, help="results JSON (default $CORNELL_RUN_DIR/equal_time_RES.json)")
    ap.add_argument("--report", default=None, metavar="JSON", help="only print the table of a results JSON")
    ap.add_argument("--main-only", action="store_true", help="with --report: leave out the bracket runs")
    ap.add_argument("--reference-only", action="store_true")
    ap.add_argument("--study-only", action="store_true")
    ap.add_argument("--redo-study", action="store_true")
    a = ap.parse_args()
    set_spectral(a.spectral or "--spectral" in common.NULLPATH_ARGS)
    if a.report:
        return report(a.report, a.main_only)
    if a.no_study and not a.sampler:
        sys.exit("--no-study needs --sampler")

    t_begin = time.time()
    nc, ns = (int(x) for x in a.ref_nullpath.split("x"))
    mc, ms = (int(x) for x in a.ref_mitsuba.split("x"))
    print("== reference (%d x %d spp nullpath, %d x %d spp Mitsuba %s, %d threads)" % (
        nc, ns, mc, ms, MI_REF_VARIANT, a.ref_threads), flush=True)
    R = build_reference(a.res, nc, ns, mc, ms, a.ref_threads, a.ref_mitsuba_sampler)
    if a.reference_only:
        return
    if a.no_study:
        st = {"best": None}
    else:
        print("== Mitsuba samplers", flush=True)
        st = sampler_study(R, a.res, [int(x) for x in a.study_spp.split(",")], a.study_seeds, 2,
                           force=a.redo_study)
        print_study(st)
    if a.study_only:
        return
    sampler = a.sampler or st["best"]
    cfgs = [{"name": "nullpath", "renderer": "nullpath", "args": MODE["nullpath_args"]},
            {"name": "mitsuba-llvm-" + sampler, "renderer": "mitsuba", "variant": MODE["llvm"], "sampler": sampler}]
    for extra in (x for x in a.extra_sampler.split(",") if x and x != sampler):
        cfgs.append({"name": "mitsuba-llvm-" + extra, "renderer": "mitsuba", "variant": MODE["llvm"],
                     "sampler": extra})
    if not a.no_scalar:
        cfgs.append({"name": "mitsuba-scalar-" + sampler, "renderer": "mitsuba", "variant": MODE["scalar"],
                     "sampler": sampler})
    lo, hi = (int(x) for x in a.calib_spp.split(","))
    results = {"machine": {"node": platform.node(), "cpus": os.cpu_count(), "load_avg_start": os.getloadavg()},
               "args": vars(a), "reference": R["info"], "sampler": sampler, "study_best": st["best"],
               "calibration": {}, "cells": [], "spectral": MODE["spectral"],
               "nullpath_args": common.NULLPATH_ARGS + MODE["nullpath_args"], "table": {}}
    out_path = a.out or os.path.join(common.RUN_DIR, "equal_time_%d%s.json" % (a.res, MODE["suffix"]))
    for threads in (int(x) for x in a.threads.split(",")):
        print("== %d thread(s)" % threads, flush=True)
        table_s = None
        if MODE["spectral"]:
            results["table"][str(threads)] = measure_table(threads, a.res)
            table_s = results["table"][str(threads)]["table_s"]
        for budget in (float(x) for x in a.budgets.split(",")):
            # calibrated right before each cell: the shared machine's load drifts within minutes
            fit = calibrate(cfgs, threads, a.res, lo, hi)
            results["calibration"]["%d_%g" % (threads, budget)] = fit
            # jobs of one round: (config, spp, label). A Mitsuba sampler whose valid counts miss the
            # target by more than 10 % (ldsampler: powers of 4; orthogonal: prime squares) runs at
            # the valid counts on both sides of it, and its MSE and wall at the target count are
            # interpolated (log-log in spp) between the two.
            jobs, bracketed = [], {}
            for c in cfgs:
                f = fit[c["name"]]
                target = max(1.0, (budget - f["startup_s"]) / f["per_spp_s"])
                if c["renderer"] == "nullpath" or c["sampler"] in ("independent", "multijitter"):
                    jobs.append((c, max(1, int(round(target))), c["name"]))
                    continue
                near = valid_spp(c["sampler"], target)
                if abs(np.log(near / target)) <= np.log(1.1):
                    jobs.append((c, near, c["name"]))
                    continue
                s_lo, s_hi = bracket_spp(c["sampler"], target)
                bracketed[c["name"]] = (c["name"] + "@%d" % s_lo, c["name"] + "@%d" % s_hi, target)
                jobs += [(c, s_lo, c["name"] + "@%d" % s_lo), (c, s_hi, c["name"] + "@%d" % s_hi)]
            runs = []
            for rep in range(a.reps):
                order = jobs if rep % 2 == 0 else jobs[::-1]
                for c, spp, label in order:
                    seed = 5000 + 100 * rep + threads * 10 + int(budget)
                    r = run_config(c, spp, threads, seed, a.res,
                                   "et_%s_t%d_b%g_r%d" % (label, threads, budget, rep))
                    e = errors(common.load_image(r), R)
                    rec = {"name": label, "config": c["name"], "rep": rep, "budget_s": budget, "threads": threads,
                           **{k: r[k] for k in ("spp", "seed", "wall_s", "cpu_s", "startup_s", "render_s", "cmd")},
                           **e}
                    runs.append(rec)
                    print("  %g s, %d thr, round %d: %-28s %5d spp  wall %.2f s (start-up %.2f)  CPU %.2f s  "
                          "RMSE %.5f" % (budget, threads, rep, label, rec["spp"], rec["wall_s"], rec["startup_s"],
                                         rec["cpu_s"], max(rec["mse"], 0) ** 0.5), flush=True)
            cell = {"threads": threads, "budget_s": budget, "runs": runs, "nullpath_table_s": table_s,
                    "labels": list(dict.fromkeys(j[2] for j in jobs)),
                    "bracketed": {k: list(v) for k, v in bracketed.items()}}
            summarize_cell(cell)
            results["cells"].append(cell)
            with open(out_path, "w") as f:
                json.dump(results, f, indent=1)
    results["load_avg_end"] = os.getloadavg()
    results["wall_s_total"] = time.time() - t_begin
    with open(out_path, "w") as f:
        json.dump(results, f, indent=1)
    print_table(results)
    print("written", out_path)


def summarize_cell(cell):
    """Per label: mean MSE over the rounds, walls, CPU; bracketed samplers interpolated; ratios."""
    budget, runs = cell["budget_s"], cell["runs"]
    by = {}
    for label in cell["labels"]:
        rr = [x for x in runs if x["name"] == label]
        mse = float(np.mean([x["mse"] for x in rr]))
        by[label] = {
            "spp": rr[0]["spp"], "wall_s": float(np.mean([x["wall_s"] for x in rr])),
            "wall_s_each": [x["wall_s"] for x in rr],
            "startup_s": float(np.mean([x["startup_s"] for x in rr])),
            "render_s": float(np.mean([x["render_s"] for x in rr])),
            "cpu_s": float(np.mean([x["cpu_s"] for x in rr])),
            "mse": mse, "rmse": max(mse, 0) ** 0.5,
            "rmse_each": [max(x["mse"], 0) ** 0.5 for x in rr],
            "rmse_vs_nullpath_ref": max(float(np.mean([x["mse_vs_nullpath"] for x in rr])), 0) ** 0.5,
            "rmse_vs_mitsuba_ref": max(float(np.mean([x["mse_vs_mitsuba"] for x in rr])), 0) ** 0.5,
        }
    for name, (la, lb, target) in cell["bracketed"].items():
        pa, pb = by[la], by[lb]
        t = float((np.log(target) - np.log(pa["spp"])) / (np.log(pb["spp"]) - np.log(pa["spp"])))

        def lerp(u, v):
            return float(np.exp((1 - t) * np.log(max(u, 1e-30)) + t * np.log(max(v, 1e-30))))
        st_ = (1 - t) * pa["startup_s"] + t * pb["startup_s"]
        wall = lerp(pa["wall_s"], pb["wall_s"])
        mse = lerp(pa["mse"], pb["mse"])
        by[name] = {"spp": "%d-%d" % (pa["spp"], pb["spp"]), "spp_target": target, "wall_s": wall,
                    "startup_s": st_, "render_s": wall - st_, "cpu_s": lerp(pa["cpu_s"], pb["cpu_s"]),
                    "mse": mse, "rmse": mse ** 0.5, "interpolated_from": [la, lb], "interpolation_t": t}
    for b in by.values():
        # MSE taken as inversely proportional to the time spent: the RMSE the run would have had
        # with exactly the budget (wall) or exactly budget x threads of CPU
        b["rmse_time_scaled"] = max(b["mse"] * b["wall_s"] / budget, 0) ** 0.5
        b["rmse_cpu_scaled"] = max(b["mse"] * b["cpu_s"] / (budget * cell["threads"]), 0) ** 0.5
    base = by["nullpath"]
    tab = cell.get("nullpath_table_s")
    if tab is not None:
        # nullpath's spectral table optimisation (one-off per process) taken out of its wall
        base["rmse_time_scaled_no_table"] = max(base["mse"] * max(base["wall_s"] - tab, 1e-3) / budget, 0) ** 0.5
    for label, b in by.items():
        for k in ("rmse", "rmse_time_scaled", "rmse_cpu_scaled"):
            b[k + "_ratio"] = b[k] / max(base[k], 1e-30)
        if tab is not None:
            own = b["rmse_time_scaled_no_table"] if label == "nullpath" else b["rmse_time_scaled"]
            b["rmse_time_scaled_no_table_ratio"] = own / max(base["rmse_time_scaled_no_table"], 1e-30)
    cell["by"] = by
    return cell


def print_table(results, main_only=False):
    ref = results["reference"]
    print("\n== equal-time RMSE (%s; reference noise rmse %.1e subtracted; mean MSE over %d rounds)" % (
        "%dx%d" % (results["args"]["res"], results["args"]["res"]), ref["mse_ref"] ** 0.5, results["args"]["reps"]))
    spec = any(c.get("nullpath_table_s") is not None for c in results["cells"])
    print("| threads | budget s | renderer | spp | wall s (start-up + render) | CPU s | RMSE | ÷ nullpath | "
          "÷ nullpath, time-scaled | ÷ nullpath, CPU-scaled |" + (" ÷ nullpath, time-scaled, no table |" if spec else ""))
    print("|---|---|---|---|---|---|---|---|---|---|" + ("---|" if spec else ""))
    for cell in results["cells"]:
        for name, b in cell["by"].items():
            if main_only and "@" in name:
                continue
            print("| %d | %g | %s | %s | %.2f (%.2f + %.2f) | %.2f | %.5f | %.2f | %.2f | %.2f |" % (
                cell["threads"], cell["budget_s"], name, b["spp"], b["wall_s"], b["startup_s"], b["render_s"],
                b["cpu_s"], b["rmse"], b["rmse_ratio"], b["rmse_time_scaled_ratio"], b["rmse_cpu_scaled_ratio"])
                + (" %.2f |" % b["rmse_time_scaled_no_table_ratio"] if spec else ""))
        if cell.get("nullpath_table_s") is not None:
            print("| %d | %g | (nullpath's table optimisation: %.2f s of its wall) | | | | | | | | |"
                  % (cell["threads"], cell["budget_s"], cell["nullpath_table_s"]))


def report(path, main_only):
    """Re-summarize a results JSON (older files: bracket targets from their calibration)."""
    with open(path) as f:
        results = json.load(f)
    for cell in results["cells"]:
        if "labels" not in cell:
            cell["labels"] = list(dict.fromkeys(x["name"] for x in cell["runs"]))
            cell["bracketed"] = {}
            cal = results["calibration"]
            fit = cal.get("%d_%g" % (cell["threads"], cell["budget_s"])) or cal[str(cell["threads"])]
            for label in cell["labels"]:
                if "@" in label:
                    name = label.split("@")[0]
                    if name not in cell["bracketed"]:
                        f_ = fit[name]
                        target = max(1.0, (cell["budget_s"] - f_["startup_s"]) / f_["per_spp_s"])
                        pair = [x for x in cell["labels"] if x.startswith(name + "@")]
                        cell["bracketed"][name] = [pair[0], pair[1], target]
        summarize_cell(cell)
    print_table(results, main_only)

if __name__ == "__main__":
    main()
