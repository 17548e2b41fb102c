#!/usr/bin/python3
"""Picture of a packing written by pack_spheres: front (x-y) and side (z-y) views of the
spheres, shaded by depth, and the solid-fraction profile from the JSON report.

    tools/pack_spheres/plot_packing.py packing.csv report.json packing.png

Needs matplotlib (Debian: python3-matplotlib); not used by the build or the tests.
"""
import csv
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    csv_path, report_path, png_path = sys.argv[1:]
    with open(csv_path) as f:
        spheres = [tuple(map(float, (row["x"], row["y"], row["z"], row["r"]))) for row in csv.DictReader(f)]
    with open(report_path) as f:
        rep = json.load(f)
    lx, ly, lz = rep["input"]["duct"]
    bed = rep["bed"]
    hold = rep["input"]["hold_width"]

    fig, axes = plt.subplots(1, 3, figsize=(11, 7), gridspec_kw={"width_ratios": [1, 1, 1.2]})
    cmap = plt.get_cmap("viridis")
    for ax, (h, depth, lh, name) in zip(axes[:2], [(0, 2, lx, "x"), (2, 0, lz, "z")]):
        ld = lz if depth == 2 else lx
        # Far spheres first, near ones on top.
        for s in sorted(spheres, key=lambda s: -s[depth]):
            ax.add_patch(Circle((s[h], s[1]), s[3], facecolor=cmap(s[depth] / ld), edgecolor="k", lw=0.4))
        ax.add_patch(Rectangle((0, 0), lh, ly, fill=False, lw=1.2))
        for x0 in (0, lh - hold):
            ax.add_patch(Rectangle((x0, 0), hold, ly, color="tab:red", alpha=0.12, lw=0))
        ax.axhline(bed["base"], color="tab:red", lw=0.8, ls=":")
        ax.axhline(bed["surface_height"], color="tab:red", lw=0.8, ls="--")
        ax.set_xlim(-0.005, lh + 0.005)
        ax.set_ylim(-0.005, ly + 0.005)
        ax.set_aspect("equal")
        ax.set_xlabel(f"{name} (m)")
        ax.set_ylabel("y (m)")
        ax.set_title(f"{name}-y view, shade: {'z' if depth == 2 else 'x'}")
    ax = axes[2]
    prof = rep["solid_fraction_profile"]
    ax.plot(prof["phi"], prof["y"], "k-", lw=1)
    lo, hi = rep["input"].get("interior", [0.10, 0.25])
    ax.axhspan(lo, hi, color="tab:blue", alpha=0.1, label=f"interior {lo:.2f}-{hi:.2f} m")
    ax.axhline(bed["base"], color="tab:red", lw=0.8, ls=":", label="support")
    ax.axhline(bed["surface_height"], color="tab:red", lw=0.8, ls="--", label="surface")
    v = rep["voidage_settled"]
    ax.set_title(f"solid fraction, slabs of d/4\nvoidage bulk {v['bulk']:.3f}, core {v['core']:.3f}")
    ax.set_xlabel("solid fraction")
    ax.set_ylim(-0.005, ly + 0.005)
    ax.set_xlim(0, 1)
    ax.legend(loc="upper right", fontsize=8)
    fig.suptitle(f"pack_spheres: N = {rep['N']}, d = {rep['input']['diameter']} m, seed {rep['input']['seed']}"
                 f" (red bands: {hold * 100:.1f} cm hold layer)")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    main()
