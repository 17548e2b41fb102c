#!/usr/bin/python3
"""Figures 4-8 of the paper's porous bed from a set of runs (one per mu_S) of porous_bed.yaml,
plus the Ergun prediction (paper Eq. 23) for the packing's measured voidage (packing.json).
Python 3 + numpy + matplotlib + h5py (Debian python3-*).

    cases/porous_bed/plots.py -o DIR --run output/pb/mu_100 100 --run output/pb/mu_1000 1000 [--title T]
        [--time T] [--csv results.csv] [--rigid RIGID_RUN] [--digests DIGEST_DIR]

A --run is a run's output folder or its digest (voigt_post/porous_bed.py: DIR/<run id>.npz, the numbers these
figures need at the run's end, committed in cases/porous_bed/digests/ so that a run's figures
outlive the machine it ran on). With --digests DIR, one digest per finished run folder is
written there.

Writes DIR/pressure_midline.png (Fig. 4), gradient_midline.png (Fig. 5), gradient_vs_modulus.png
(Fig. 6: mean -dp/dy over y = 0.10-0.25 m, linear fit, slope, intercept, R^2), pressure_slice.png
(Fig. 7: mid-plane z, lowest and highest mu_S), deformation.png (Fig. 8: psi = 0 in the mid-plane
at the first, middle and last output, and the bed centroid's rise against time), and prints a
markdown table, which also has the gradient of the section-averaged pressure (section_gradient).
The midline is the probe `midline` (probe_midline.csv) at its last time, or with
--time T the pressure field of the last output at or before T (mean of the four cell columns
around x = z = 5.5 cm; cell centres), so runs can be compared at an earlier common time; Figs. 7-8
then stop at that output too. With --csv FILE, one row per finished run (results_row) is merged
into FILE by run id (issue 22's results.csv; runs not finished and --time are left out).
"""
import argparse
import json
import os

import matplotlib
import numpy as np
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from voigt_post import ergun, series  # noqa: E402
from voigt_post.porous_bed import PACKING, RunDir, Y0, Y1, load, peak_rise, scene, write_digest  # noqa: E402


def results_row(run, summ, t, mean, section, rise, peak=None):
    """Issue 22's porous-bed table: one finished run (a RunDir or Digest and its summary.json)."""
    ls = summ.get("level_set", {})
    sharp0 = ls.get("sharp_volume_initial")
    return dict(series.run_row(run.run_id, summ), **{
        "midline_t": "%.4f" % t,
        "mean_gradient": "%.1f" % mean,
        "section_gradient": "%.1f" % section,
        "centroid_rise_mm": "" if rise is None else "%.2f" % rise,
        # The paper's "the bed deforms about 10 mm vertically": the largest rise, and when.
        "peak_rise_mm": "" if peak is None else "%.2f" % peak[0],
        "peak_rise_s": "" if peak is None else "%.3f" % peak[1],
        # What the global correction holds (INT H) and the sharp volume (psi > 0), in per cent.
        "volume_change_pct": series.fmt(100 * ls["volume_drift"] if "volume_drift" in ls else None, "%.2f"),
        "sharp_volume_change_pct": series.fmt(100 * (ls["sharp_volume"] / sharp0 - 1) if sharp0 else None, "%.2f"),
    })


def digest(run, folder):
    """A finished run's digest, unless one newer than its summary.json is there already (a
    rewrite of the same numbers would still change the file: the .npz holds time stamps)."""
    path = os.path.join(folder, run.run_id + ".npz")
    summ = os.path.join(run.d, "summary.json")
    if os.path.exists(path) and os.path.getmtime(path) >= os.path.getmtime(summ):
        return
    os.makedirs(folder, exist_ok=True)
    write_digest(run, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", nargs=2, action="append", metavar=("DIR", "MU_S"), required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("--time", type=float, help="midline from the last field output at or before this time")
    ap.add_argument("-o", "--outdir", required=True)
    ap.add_argument("--csv", help="merge one row per finished run into this CSV (results.csv)")
    ap.add_argument("--rigid", metavar="DIR", help="a run of rigid_bed.py's scene (the very stiff limit): its mean "
                    "gradient is drawn in Fig. 6 and printed beside Ergun's")
    ap.add_argument("--digests", metavar="DIR", help="write DIR/<run id>.npz for every finished run folder")
    a = ap.parse_args()
    runs = sorted(((float(m), load(d, a.time)) for d, m in a.run), key=lambda r: r[0])
    os.makedirs(a.outdir, exist_ok=True)
    sfx = ("\n" + a.title) if a.title else ""
    with open(PACKING) as f:
        pk = json.load(f)["voidage_written"]
    # Ergun's gas, inflow and sphere diameter and the gas's rho g: the runs' scene (its record).
    flow = ergun.bed_flow(scene([d for d, _ in a.run] + ([a.rigid] if a.rigid else []), "plots.py"), PACKING)
    rho_g = flow["rho"] * flow["g"]
    f4, ax4 = plt.subplots(figsize=(6, 4.5))
    f5, ax5 = plt.subplots(figsize=(6, 4.5))
    mus, grads, secs, rows, results = [], [], [], [], []
    for n, (mu, d) in enumerate(runs):
        t, y, p = d.midline()
        gr = -np.gradient(p, y)
        sel = (y >= Y0) & (y <= Y1)
        mean = float(np.mean(gr[sel]))
        c = "C%d" % n
        ax4.plot(y, p, c, label="mu_S = %g Pa (t = %.3g s)" % (mu, t))
        ax5.plot(y, gr, c, lw=0.8, label="mu_S = %g Pa" % mu)
        ax5.plot([Y0, Y1], [mean, mean], c + "--")
        tt, cy = d.centroid()
        mus.append(mu)
        grads.append(mean)
        k = int(np.argmin(np.abs(tt - t)))      # centroid rise at the midline's time
        ts, sec = d.section_gradient()
        secs.append(sec)
        rows.append((mu, t, mean, mean - rho_g, ts, sec, 1000 * (cy[k] - cy[0])))
        summ = d.summary()
        if a.csv and a.time is None and series.finished(summ):
            results.append(results_row(d, summ, t, mean, sec, rows[-1][-1], peak_rise(tt, cy)))
        if a.digests and a.time is None and isinstance(d, RunDir) and series.finished(summ):
            digest(d, a.digests)
    for ax, f, lab, name in ((ax4, f4, "pressure (Pa)", "pressure_midline.png"),
                             (ax5, f5, "-dp/dy (Pa/m); dashed: mean over 0.10-0.25 m", "gradient_midline.png")):
        ax.set_xlabel("y (m), midline x = z = 5.5 cm")
        ax.set_ylabel(lab)
        ax.axvspan(Y0, Y1, color="0.9")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        ax.set_title(("Fig. 4: pressure on the midline" if ax is ax4 else "Fig. 5: pressure gradient") + sfx, fontsize=9)
        f.tight_layout()
        f.savefig(os.path.join(a.outdir, name), dpi=80)
    # Fig. 6: linear fit of the mean gradient against mu_S (midline, and section-averaged).
    mus = np.array(mus)
    f6, ax6 = plt.subplots(figsize=(6, 4.5))
    fits = []
    for vals, mark, ls, name in ((grads, "o", "k-", "midline"), (secs, "s", "k--", "section-averaged")):
        vals = np.array(vals)
        ax6.plot(mus, vals, mark, label="Voigt, " + name)
        if len(mus) >= 3:  # two points always lie on a line
            slope, icpt = np.polyfit(mus, vals, 1)
            pred = slope * mus + icpt
            ss = np.sum((vals - vals.mean()) ** 2)
            r2 = 1 - np.sum((vals - pred) ** 2) / ss if ss > 0 else float("nan")
            fits.append((name, slope, icpt, r2))
            xs = np.linspace(0, mus.max() * 1.05, 50)
            ax6.plot(xs, slope * xs + icpt, ls, lw=0.8,
                     label="fit (%s): %.3g mu_S + %.3g Pa/m, R^2 = %.4f" % fits[-1])
    for e, lab in ((pk["interior"], "interior, full section"), (pk["interior_flow_region"], "interior, outside hold layer")):
        ax6.axhline(ergun.gradient(e, **flow), ls=":", color="C3" if "full" in lab else "C2",
                    label="Ergun, e = %.3f (%s): %.1f Pa/m" % (e, lab, ergun.gradient(e, **flow)))
    ax6.axhline(rho_g, ls="--", color="0.5", label="gas hydrostatic rho g = %.2f Pa/m" % rho_g)
    rigid = None
    if a.rigid:  # same measure (midline, y = 0.10-0.25 m) on the bed of fixed spheres
        rr = load(a.rigid, a.time)
        t_r, y_r, p_r = rr.midline()
        gr_r = -np.gradient(p_r, y_r)
        rigid = (t_r, float(np.mean(gr_r[(y_r >= Y0) & (y_r <= Y1)]))) + rr.section_gradient()
        ax6.axhline(rigid[1], ls="-.", color="C4", label="rigid bed (fixed spheres), t = %.3g s: %.1f Pa/m" % rigid[:2])
        ax6.axhline(rigid[3], ls=":", color="C4", label="rigid bed, section-averaged: %.1f Pa/m" % rigid[3])
        summ = rr.summary()
        if a.csv and a.time is None and series.finished(summ):  # its row: model "rigid", no modulus
            results.append(dict(results_row(rr, summ, t_r, rigid[1], rigid[3], None), model="rigid"))
        if a.digests and a.time is None and isinstance(rr, RunDir) and series.finished(summ):
            digest(rr, a.digests)
    ax6.set_xlabel("mu_S (Pa)")
    ax6.set_ylabel("mean -dp/dy over y = 0.10-0.25 m (Pa/m)")
    ax6.set_title("Fig. 6: gradient against shear modulus" + sfx, fontsize=9)
    ax6.legend(fontsize=7)
    ax6.grid(alpha=0.3)
    f6.tight_layout()
    f6.savefig(os.path.join(a.outdir, "gradient_vs_modulus.png"), dpi=80)
    # Fig. 7 and 8 from the HDF5 output of the lowest and highest modulus.
    ends = [runs[0], runs[-1]] if len(runs) > 1 else runs
    f7, ax7 = plt.subplots(1, len(ends), figsize=(3.8 * len(ends) + 1, 6), squeeze=False)
    f8, ax8 = plt.subplots(1, len(ends) + 1, figsize=(3.2 * len(ends) + 4, 6), squeeze=False)
    for n, (mu, d) in enumerate(ends):
        sp, fr = d.slices()  # first, middle, last output: (t, pressure, psi)
        t, p, psi = fr[-1]
        ext = [0, sp[0] * p.shape[1], 0, sp[1] * p.shape[0]]
        im = ax7[0][n].imshow(p, origin="lower", extent=ext, cmap="jet")
        ax7[0][n].contour(psi, [0], colors="k", linewidths=0.5, origin="lower", extent=ext)
        ax7[0][n].set_title("mu_S = %g Pa, t = %.3g s" % (mu, t), fontsize=9)
        f7.colorbar(im, ax=ax7[0][n], label="pressure (Pa)", shrink=0.7)
        for q, st in zip(fr, (":", "--", "-")):
            ax8[0][n].contour(q[2], [0], colors="k", linestyles=st, linewidths=0.7,
                              origin="lower", extent=ext)
            ax8[0][n].plot([], [], "k" + st, label="t = %.3g s" % q[0])
        ax8[0][n].set_title("psi = 0, mid-plane z, mu_S = %g Pa" % mu, fontsize=9)
        ax8[0][n].set_aspect("equal")
        ax8[0][n].legend(fontsize=7, loc="lower right")
    for mu, d in runs:
        tt, cy = d.centroid()
        ax8[0][-1].plot(tt, 1000 * (cy - cy[0]), label="mu_S = %g Pa" % mu)
    ax8[0][-1].set_xlabel("t (s)")
    ax8[0][-1].set_ylabel("rise of the bed's centroid (mm)")
    ax8[0][-1].legend(fontsize=7)
    ax8[0][-1].grid(alpha=0.3)
    f7.suptitle("Fig. 7: pressure, mid-plane z (black: psi = 0)" + sfx, fontsize=9)
    f8.suptitle("Fig. 8: bed deformation" + sfx, fontsize=9)
    for f, name in ((f7, "pressure_slice.png"), (f8, "deformation.png")):
        f.tight_layout()
        f.savefig(os.path.join(a.outdir, name), dpi=80)
    print("| mu_S (Pa) | t (s) | mean -dp/dy on the midline, 0.10-0.25 m (Pa/m) | minus rho g (Pa/m) "
          "| t of the last field output (s) | section-averaged -dp/dy, 0.10-0.25 m (Pa/m) | centroid rise (mm) |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %g | %.3g | %.1f | %.1f | %.3g | %.1f | %.2f |" % r)
    if a.csv:
        series.merge_csv(a.csv, results)
        print("plots.py: %d finished run(s) merged into %s" % (len(results), a.csv))
    for fit in fits:
        print("\nlinear fit (%s): slope %.4g Pa/m per Pa, intercept %.4g Pa/m, R^2 = %.4f" % fit)
    if rigid:
        print("rigid bed (rigid_bed.py, fixed spheres) at t = %.3g s: mean -dp/dy on the midline %.1f Pa/m (minus "
              "rho g %.1f); section-averaged %.1f Pa/m (t = %.3g s)" % (rigid[0], rigid[1], rigid[1] - rho_g,
                                                                      rigid[3], rigid[2]))
    print("Ergun (Eq. 23): e = %.3f -> %.1f Pa/m; e = %.3f -> %.1f Pa/m" % (
        pk["interior"], ergun.gradient(pk["interior"], **flow), pk["interior_flow_region"],
        ergun.gradient(pk["interior_flow_region"], **flow)))


if __name__ == "__main__":
    main()
