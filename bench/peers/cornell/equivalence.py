#!/usr/bin/env python3
"""Is Mitsuba's scene (mi_cornell.py) the same as nullpath's cornell-box.toml? Render each with K
independent seeds of S spp, estimate each pixel's mean and its standard error from the spread over
the seeds, and compare:

* image mean per channel: relative difference and its z (standard errors from the seeds);
* per pixel z = (m_n - m_m) / sqrt(se_n^2 + se_m^2): mean, rms (1 for agreement within noise; with
  K seeds the t-distribution's rms is sqrt(dof/(dof-2)), ~1.04 for K = 16), fraction |z| > 4;
* RMSE between the two K*S-spp images against the RMSE the noise alone gives;
* the same on 8 x 8 pixel blocks (a bias of a few pixels' worth shows there first).

  python equivalence.py [--res 128] [--spp 64] [--seeds 16] [--variant llvm_ad_rgb] [--threads 2]
  python equivalence.py --from-reference     # the same statistics from the reference's chunks
  python equivalence.py --spectral [...]     # nullpath --spectral vs Mitsuba llvm_ad_spectral
  python equivalence.py --spectral --from-reference   # equal_time.py --spectral's reference chunks

--spectral adds `--spectral` to nullpath's command ($NULLPATH_ARGS is appended too), makes the default
Mitsuba variant llvm_ad_spectral and reads the reference from ref_RES_spectral. It also compares each
renderer's spectral image mean with its RGB one (per channel ratio spectral / RGB - 1, with standard
errors), the RGB means from ref_RES/equivalence.json (equivalence.py --from-reference in RGB mode).

Images go to $CORNELL_RUN_DIR/equiv (default /work/peers-run/cornell/equiv); a summary JSON is
written there and printed.
"""
import argparse
import glob
import json
import os

import numpy as np

import common


def stats(stack):
    """Mean and standard error of the mean per pixel over axis 0, and the per-seed image means."""
    k = stack.shape[0]
    return stack.mean(0), stack.std(0, ddof=1) / np.sqrt(k), stack.reshape(k, -1, 3).mean(1)


def compare(name_a, sa, name_b, sb, block=8):
    ma, ea, ia = stats(sa)
    mb, eb, ib = stats(sb)
    mean_a, mean_b = ia.mean(0), ib.mean(0)
    se_a, se_b = ia.std(0, ddof=1) / np.sqrt(len(ia)), ib.std(0, ddof=1) / np.sqrt(len(ib))
    rel = mean_a / mean_b - 1
    z_mean = (mean_a - mean_b) / np.sqrt(se_a ** 2 + se_b ** 2)
    se = np.sqrt(ea ** 2 + eb ** 2)
    ok = se > 0
    z = np.where(ok, (ma - mb) / np.where(ok, se, 1), 0.0)
    h, w, _ = ma.shape
    hb, wb = h // block, w // block

    def blocks(x):
        return x[:hb * block, :wb * block].reshape(hb, block, wb, block, 3).mean((1, 3))

    # block means: their standard errors from the per-seed block means
    ba, bb = np.stack([blocks(x) for x in sa]), np.stack([blocks(x) for x in sb])
    bse = np.sqrt(ba.var(0, ddof=1) / len(ba) + bb.var(0, ddof=1) / len(bb))
    bz = (ba.mean(0) - bb.mean(0)) / np.where(bse > 0, bse, 1)
    worst = np.unravel_index(np.argmax(np.abs(z)), z.shape)
    return {
        "a": name_a, "b": name_b,
        "mean_rgb_a": mean_a.tolist(), "mean_rgb_b": mean_b.tolist(),
        "mean_se_a": se_a.tolist(), "mean_se_b": se_b.tolist(),
        "mean_rel_diff": rel.tolist(), "mean_z": z_mean.tolist(),
        "mean_rel_diff_se": ((mean_a / mean_b) * np.sqrt((se_a / mean_a) ** 2 + (se_b / mean_b) ** 2)).tolist(),
        "all_mean_rel_diff": float(mean_a.sum() / mean_b.sum() - 1),
        "pixel_z_mean": float(z[ok].mean()), "pixel_z_rms": float(np.sqrt((z[ok] ** 2).mean())),
        "pixel_frac_abs_z_gt_4": float((np.abs(z[ok]) > 4).mean()),
        "pixel_max_abs_z": float(np.abs(z).max()), "pixel_worst": [int(x) for x in worst],
        "pixels_compared": int(ok.sum()),
        "rmse_between": float(np.sqrt(((ma - mb) ** 2).mean())),
        "rmse_expected_from_noise": float(np.sqrt((se ** 2).mean())),
        "block": block, "block_z_rms": float(np.sqrt((bz ** 2).mean())),
        "block_max_abs_z": float(np.abs(bz).max()),
    }


def print_summary(r):
    print("%s vs %s" % (r["a"], r["b"]))
    for c, ch in enumerate("RGB"):
        print("  %s mean %.6f +- %.6f  vs  %.6f +- %.6f   rel diff %+.2e +- %.1e  z %+.2f" % (
            ch, r["mean_rgb_a"][c], r["mean_se_a"][c], r["mean_rgb_b"][c], r["mean_se_b"][c],
            r["mean_rel_diff"][c], r["mean_rel_diff_se"][c], r["mean_z"][c]))
    print("  per pixel z: mean %+.3f rms %.3f  |z|>4: %.4f%%  max |z| %.2f at %s (%d values)" % (
        r["pixel_z_mean"], r["pixel_z_rms"], 100 * r["pixel_frac_abs_z_gt_4"], r["pixel_max_abs_z"],
        r["pixel_worst"], r["pixels_compared"]))
    print("  RMSE between the means %.5f, expected from noise alone %.5f" % (
        r["rmse_between"], r["rmse_expected_from_noise"]))
    print("  %dx%d blocks: z rms %.3f, max |z| %.2f" % (r["block"], r["block"], r["block_z_rms"],
                                                        r["block_max_abs_z"]))


def spectral_vs_rgb(r, res):
    """Each renderer's spectral image mean against its RGB one (ref_RES/equivalence.json)."""
    p = os.path.join(common.RUN_DIR, "ref_%d" % res, "equivalence.json")
    if not os.path.exists(p):
        print("(no %s: run equivalence.py --from-reference in RGB mode for the spectral / RGB ratios)" % p)
        return None
    with open(p) as f:
        g = json.load(f)
    out = {}
    for who, k in (("nullpath", "a"), ("mitsuba", "b")):
        s, ss = np.array(r["mean_rgb_" + k]), np.array(r["mean_se_" + k])
        c, cs = np.array(g["mean_rgb_" + k]), np.array(g["mean_se_" + k])
        out[who] = {"spectral": s.tolist(), "rgb": c.tolist(), "rgb_from": g[k],
                    "ratio_minus_1": (s / c - 1).tolist(),
                    "se": ((s / c) * np.sqrt((ss / s) ** 2 + (cs / c) ** 2)).tolist()}
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--res", type=int, default=128)
    ap.add_argument("--spp", type=int, default=64, help="spp per seed")
    ap.add_argument("--seeds", type=int, default=16)
    ap.add_argument("--variant", default=None, help="default llvm_ad_rgb, with --spectral llvm_ad_spectral")
    ap.add_argument("--spectral", action="store_true", help="nullpath --spectral vs a Mitsuba spectral variant")
    ap.add_argument("--sampler", default="independent")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--from-reference", action="store_true",
                    help="use the chunks equal_time.py rendered for its reference")
    a = ap.parse_args()
    spectral = a.spectral or "--spectral" in common.NULLPATH_ARGS
    nargs = ["--spectral"] if spectral else []
    a.variant = a.variant or ("llvm_ad_spectral" if spectral else "llvm_ad_rgb")
    sfx = "_spectral" if spectral else ""

    if a.from_reference:
        d = os.path.join(common.RUN_DIR, "ref_%d%s" % (a.res, sfx))
        n_files = sorted(glob.glob(os.path.join(d, "nullpath_seed*.exr")))
        m_files = sorted(glob.glob(os.path.join(d, "mitsuba_seed*.npy")))
        sn = np.stack([common.load_image(p) for p in n_files])
        sm = np.stack([common.load_image(p) for p in m_files])
        with open(os.path.join(d, "chunks.json")) as f:
            meta = json.load(f)
        r = compare("nullpath%s %d x %d spp" % (" --spectral" if spectral else "", len(n_files), meta["nullpath_spp"]), sn,
                    "mitsuba %s/%s %d x %d spp" % (meta["mitsuba_variant"], meta.get("mitsuba_sampler", "independent"),
                                                   len(m_files), meta["mitsuba_spp"]), sm)
        out = os.path.join(d, "equivalence.json")
    else:
        d = os.path.join(common.RUN_DIR, "equiv" + sfx)
        os.makedirs(d, exist_ok=True)
        sn, sm = [], []
        for s in range(a.seeds):
            # alternate the two renderers; seeds 1000+ keep these independent of other runs
            rn = common.run_nullpath(a.spp, a.threads, 1000 + s, a.res,
                                     os.path.join(d, "n_%d_%d_%d.exr" % (a.res, a.spp, s)), nargs)
            rm = common.run_mitsuba(a.variant, a.sampler, a.spp, a.threads, 1000 + s, a.res,
                                    os.path.join(d, "m_%s_%s_%d_%d_%d.npy" % (a.variant, a.sampler, a.res, a.spp, s)))
            sn.append(common.load_image(rn))
            sm.append(common.load_image(rm))
            print("seed %d: nullpath %.2f s, mitsuba %.2f s" % (s, rn["wall_s"], rm["wall_s"]), flush=True)
        r = compare("nullpath%s %d x %d spp" % (" --spectral" if spectral else "", a.seeds, a.spp), np.stack(sn),
                    "mitsuba %s/%s %d x %d spp" % (a.variant, a.sampler, a.seeds, rm["spp"]), np.stack(sm))
        out = os.path.join(d, "equivalence_%d_%dx%d_%s.json" % (a.res, a.seeds, a.spp, a.variant))
    if spectral:
        r["spectral_vs_rgb"] = spectral_vs_rgb(r, a.res)
    with open(out, "w") as f:
        json.dump(r, f, indent=1)
    print_summary(r)
    if spectral and r["spectral_vs_rgb"]:
        for who, v in r["spectral_vs_rgb"].items():
            print("  %s spectral / RGB - 1 (R, G, B): %s" % (who, ", ".join(
                "%+.2f %% +- %.2f" % (100 * x, 100 * e) for x, e in zip(v["ratio_minus_1"], v["se"]))))
    print("written", out)


if __name__ == "__main__":
    main()
