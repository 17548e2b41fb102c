#!/usr/bin/python3
"""What accuracy costs in time on the paper's own scene (issue 22 item 4): the falling block's
measures at mu_S = 1000 on 30^3 to 75^3 against the cost of each run, both interface models.
Python 3 + matplotlib. Reads grid_cost.csv (one row per run, its source named), writes PNG.

    cases/falling_block/grid_cost.py -o cases/falling_block/grid_cost.png

Cost is cell-steps (cells x steps), which does not depend on the machine; the wall time of
each run is printed beside its point (ranks and conditions in the CSV's source column).
"""
import argparse
import csv
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PANELS = [("slowing_s", "first impact: mean vy stops falling (s)", "paper ~0.06 s", 0.06),
          ("first_bending_mm", "first bending peak (mm)", None, None),
          ("base_gap_s", "base reached: gap < 2 h from (s)", "paper ~0.36 s", 0.36),
          ("volume_change_pct", "volume change at 0.5 s (%; extend: sharp, INT H held)", None, 0.0)]


def main():
    here = os.path.dirname(os.path.realpath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--csv", default=os.path.join(here, "grid_cost.csv"))
    a = ap.parse_args()
    with open(a.csv) as f:
        rows = list(csv.DictReader(f))
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    for ax, (key, label, ref_label, ref) in zip(axes.flat, PANELS):
        for model, mark in (("integrate", "s-"), ("extend", "o-")):
            rs = sorted((r for r in rows if r["model"] == model), key=lambda r: int(r["cells"]))
            x = [int(r["cells"]) ** 3 * int(r["steps"]) for r in rs]
            y = [float(r[key]) for r in rs]
            name = "integrate (paper's model, no correction)" if model == "integrate" else "extend + global correction (default)"
            ax.plot(x, y, mark, label=name)
            for r, xi, yi in zip(rs, x, y):
                ax.annotate("%s^3\n%.0f s" % (r["cells"], float(r["wall_s"])), (xi, yi), fontsize=7,
                            textcoords="offset points", xytext=(4, 4))
        if ref is not None:
            ax.axhline(ref, color="grey", lw=0.8, ls=":")
            if ref_label:
                ax.text(ax.get_xlim()[0], ref, " " + ref_label, fontsize=7, va="bottom", color="grey")
        ax.set_xscale("log")
        ax.set_xlabel("cost: cell-steps to t = 0.5 s")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes.flat[0].legend(fontsize=8)
    fig.suptitle("Falling block, mu_S = 1000 Pa: measures against cost (30^3, 36^3, 48^3, 75^3; wall time at each point)")
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print("wrote", a.output)


if __name__ == "__main__":
    main()
