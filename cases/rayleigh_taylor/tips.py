#!/usr/bin/env python3
"""Bubble and spike tip heights of a rayleigh_taylor run, against published curves.

    tips.py OUTDIR [OUTDIR ...] [--png tips.png] [--snapshots snapshots.png]

Reads OUTDIR/fields.xdmf (times, cell size) and the psi field of every
fields_NNNNNN.h5, finds the psi zero crossings in the two cell columns next
to each axis (bubble: x = 0, highest crossing; spike: x = 1/2, lowest) and
extrapolates to the axis with y(0) = (9 y(h/2) - y(3h/2)) / 8 (the interface
is even about the axis), exactly as tests/levelset/test_rayleigh_taylor.cpp.
Prints t*, t_T, and the displacements from y = 2, and writes tips.csv into
each OUTDIR. Several OUTDIRs (e.g. two resolutions) share one plot.
The set-up's numbers (wavelength H, the unperturbed interface y = 2H, Atwood
number A and g, so t_T = t sqrt(A g / H); the densities and the domain of the
snapshots) come from each OUTDIR's scene record (scene.yaml); a run from
before records (2026-12-02) is read as the case's rayleigh_taylor.yaml.

Reference curves (displacements from 2H in units of H against t_T), read off
digitised figures at every 0.25:
  He, Chen & Zhang (1999), J. Comput. Phys. 152, 642, Re = 256 (this set-up):
    digitised by the Lethe project, examples/multiphysics/
    rayleigh-taylor-instability/ref_He_et_al_data.txt (y/4H against t*).
  Fakhari, Mitchell, Leonardi & Bolster (2017), Phys. Rev. E 96, 053301,
    Fig. 6, Re = 3000, Ca = 0.26, Pe = 1000 (phase-field LBM, weak surface
    tension): digitised by CEA's LBM_Saclay (run_training_lbm/
    TestCase08_Rayleigh-Taylor2D/RT2D_{Bubble,Spike}_Ref_Fakhari_PRE2017.dat).
"""
import argparse
import os
import sys

import numpy as np

from voigt_post import fields, scene_record
from voigt_post.xdmf import frames

HERE = os.path.dirname(os.path.realpath(__file__))

HE1999 = [  # t_T, bubble, spike
    (0.25, 0.113, -0.121), (0.50, 0.161, -0.165), (0.75, 0.213, -0.243), (1.00, 0.274, -0.348),
    (1.25, 0.348, -0.469), (1.50, 0.419, -0.602), (1.75, 0.483, -0.740), (2.00, 0.545, -0.873),
    (2.25, 0.609, -0.995), (2.50, 0.675, -1.125), (2.75, 0.739, -1.263), (3.00, 0.803, -1.403),
    (3.25, 0.870, -1.554), (3.50, 0.932, -1.724)]
FAKHARI2017 = [
    (0.25, 0.115, -0.117), (0.50, 0.156, -0.170), (0.75, 0.218, -0.257), (1.00, 0.288, -0.371),
    (1.25, 0.359, -0.496), (1.50, 0.429, -0.622), (1.75, 0.495, -0.747), (2.00, 0.557, -0.865),
    (2.25, 0.620, -0.989), (2.50, 0.685, -1.120), (2.75, 0.757, -1.259), (3.00, 0.833, -1.421)]


def crossings(col, h, y0=0.0):
    """Heights where psi changes sign along one column (cell centres)."""
    ys = []
    for j in range(len(col) - 1):
        a, b = col[j], col[j + 1]
        if (a > 0) != (b > 0):
            ys.append(y0 + (j + 0.5) * h + h * a / (a - b))
    return ys


def tips(psi, h):
    """Bubble and spike heights on the axes; psi[y, x] of one z layer."""
    b = [max(crossings(psi[:, c], h)) for c in (0, 1)]
    s = [min(crossings(psi[:, -1 - c], h)) for c in (0, 1)]
    return (9 * b[0] - b[1]) / 8, (9 * s[0] - s[1]) / 8


def setup(outdir):
    """The run's wavelength H, interface height y0, time unit sqrt(H / (A g)) (t_T = t / it),
    light and heavy densities and domain (lo, hi), from its scene record."""
    sc = scene_record.scene_or(outdir, os.path.join(HERE, "rayleigh_taylor.yaml"), "tips.py")
    ls = scene_record.level_set(sc)
    heavy, light = (float(scene_record.material(sc, n)["density"]) for n in (ls["phase"], sc["fluid"]))
    A, g = (heavy - light) / (heavy + light), -float(sc["gravity"][1])
    H = float(ls["shape"]["wavelength"])
    return {"H": H, "y0": float(ls["shape"]["point"][1]), "unit": np.sqrt(H / (A * g)), "rho": (light, heavy),
            "box": scene_record.extent(sc)}


def analyse(outdir):
    fr = frames(outdir)
    h = fr[0].spacing[1]  # vertical cell size: the crossings are along y
    su = setup(outdir)
    rows = []
    for t, path, *_ in fr:
        psi = fields.read(path, "psi")[0]  # [z, y, x] -> [y, x]
        b, s = tips(psi, h)
        rows.append((t, t / su["unit"], (b - su["y0"]) / su["H"], (s - su["y0"]) / su["H"]))
    rows = np.array(rows)
    np.savetxt(os.path.join(outdir, "tips.csv"), rows, delimiter=",", fmt="%.6f",
               header="t_star,t_T,bubble,spike", comments="")
    return rows, h / su["H"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdirs", nargs="+")
    ap.add_argument("--png", help="plot of the tip displacements against t_T")
    ap.add_argument("--snapshots", help="density snapshots of the first OUTDIR at t_T = 1, 1.5, 2, 2.5")
    args = ap.parse_args()
    he, fk = np.array(HE1999), np.array(FAKHARI2017)
    runs = []
    for d in args.outdirs:
        rows, h = analyse(d)
        runs.append((d, rows, h))
        print(f"{d}: h = 1/{round(1 / h)}")
        print("   t*     t_T   bubble  (He)    spike   (He)")
        for t, tT, b, s in rows:
            if abs(tT * 4 - round(tT * 4)) < 1e-6 or abs(t * 2 - round(t * 2)) < 1e-6:
                hb = np.interp(tT, he[:, 0], he[:, 1]) if tT >= he[0, 0] else np.nan
                hs = np.interp(tT, he[:, 0], he[:, 2]) if tT >= he[0, 0] else np.nan
                print(f"  {t:5.2f}  {tT:5.3f}  {b:+.4f} ({hb:+.3f})  {s:+.4f} ({hs:+.3f})")
    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.4, 4.8))
        ax.plot(he[:, 0], he[:, 1], "ko", mfc="none", label="He et al. 1999 (Re 256)")
        ax.plot(he[:, 0], he[:, 2], "ko", mfc="none")
        ax.plot(fk[:, 0], fk[:, 1], "k^", mfc="none", ms=5, label="Fakhari et al. 2017 (Re 3000, Ca 0.26)")
        ax.plot(fk[:, 0], fk[:, 2], "k^", mfc="none", ms=5)
        for d, rows, h in runs:
            line, = ax.plot(rows[:, 1], rows[:, 2], "-", label=f"Voigt h = 1/{round(1 / h)}")
            ax.plot(rows[:, 1], rows[:, 3], "-", color=line.get_color())
        ax.axhline(0, color="0.8", lw=0.8)
        ax.set_xlabel(r"$t_T = t\,\sqrt{A g / H}$")
        ax.set_ylabel("tip displacement from y = 2H  [H]   (bubble > 0, spike < 0)")
        ax.set_title("Rayleigh-Taylor, A = 0.5, Re = 256")
        ax.legend(fontsize=8, loc="lower left")
        fig.tight_layout()
        fig.savefig(args.png, dpi=110)
    if args.snapshots:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        d, rows, h = runs[0]
        fr = frames(d)
        su = setup(d)
        (x0, y0, _), (x1, y1, _) = su["box"]
        fig, axs = plt.subplots(1, 4, figsize=(8, 4.8), sharey=True)
        for ax, tT in zip(axs, (1.0, 1.5, 2.0, 2.5)):
            t, path = min(fr, key=lambda f: abs(f.t / su["unit"] - tT))[:2]
            rho = fields.read(path, "density")[0]
            full = np.hstack([rho[:, ::-1], rho, rho[:, ::-1]])  # mirror: one and a half wavelengths
            ax.imshow(full, origin="lower", extent=[2 * x0 - x1, 2 * x1 - x0, y0, y1], cmap="coolwarm",
                      vmin=su["rho"][0], vmax=su["rho"][1])
            ax.set_title(f"$t_T$ = {t / su['unit']:.2f}", fontsize=9)
            ax.set_xticks([0, 0.5])
        axs[0].set_ylabel("y [H]")
        fig.suptitle(f"density, h = 1/{round(1 / h)} (half wavelength computed, mirrored)", fontsize=9)
        fig.tight_layout()
        fig.savefig(args.snapshots, dpi=110)


if __name__ == "__main__":
    sys.exit(main())
