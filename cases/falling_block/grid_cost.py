#!/usr/bin/python3
"""What accuracy costs in time on the paper's own scene (issue 22 item 4): the falling block's
measures at mu_S = 1000 on 30^3 to 75^3 against the cost of each run, both interface models.
Python 3 + matplotlib. Reads the runs' rows of results.csv (events.py's columns; run ids
mu1000_<model><tag>_<n>), writes a PNG and prints the table it drew.

    cases/falling_block/grid_cost.py -o cases/falling_block/grid_cost.png [--tag +global+exact]
        [--legacy cases/falling_block/grid_cost.csv]

Cost is cell-steps (cells x steps), which does not depend on the machine; the wall time of
each run (results.csv wall_s, its ranks) is printed beside its point. --legacy also draws the
approximate-projection set of 2026-12-03 (grid_cost.csv, copied from that day's README), faint.
"""
import argparse
import csv
import os
import re

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.realpath(__file__))
# (results.csv column, grid_cost.csv column, axis label, reference label, reference value)
PANELS = [("slowing_s", "slowing_s", "first impact: mean vy stops falling (s)", "paper ~0.06 s", 0.06),
          ("first_bending_peak_mm", "first_bending_mm", "first bending peak (mm)", None, None),
          ("base_within_2h_s", "base_gap_s", "base reached: gap < 2 h from (s)", "paper ~0.36 s", 0.36),
          ("sharp_volume_change_pct", "volume_change_pct", "block volume (psi > 0) change at 0.5 s (%)", None, 0.0)]
MODELS = (("integrate", "s-", "integrate (the paper's model)"), ("extend", "o-", "extend (the default)"))


def runs(path, tag, mu=1000):
    """{model: [(n, row)]} of the finished runs mu<mu>_<model><tag>_<n> (n^3 grids), by n."""
    pat = re.compile(r"mu%d_(\w+)%s_(\d+)$" % (mu, re.escape(tag)))
    out = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            m = pat.match(r["run_id"])
            if m and r.get("t_end") and abs(float(r["t_end"]) - 0.5) < 1e-6:
                out.setdefault(m.group(1), []).append((int(m.group(2)), r))
    return {k: sorted(v, key=lambda p: p[0]) for k, v in out.items()}


def num(v):
    return float(v) if v not in (None, "") else float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--results", default=os.path.join(HERE, "results.csv"))
    ap.add_argument("--tag", default="+global+exact", help="the run ids' correction and projection tag")
    ap.add_argument("--legacy", help="grid_cost.csv: the approximate-projection set, drawn faint")
    a = ap.parse_args()
    got = runs(a.results, a.tag)
    if not got:
        raise SystemExit("grid_cost.py: no finished mu1000_<model>%s_<n> rows in %s" % (a.tag, a.results))
    legacy = []
    if a.legacy:
        with open(a.legacy) as f:
            legacy = list(csv.DictReader(f))
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.5))
    for ax, (key, old_key, label, ref_label, ref) in zip(axes.flat, PANELS):
        for n_model, (model, mark, name) in enumerate(MODELS):
            rs = got.get(model, [])
            x = [n ** 3 * int(r["steps"]) for n, r in rs]
            y = [num(r[key]) for _, r in rs]
            ax.plot(x, y, mark, color="C%d" % n_model, label=name + " " + a.tag)
            for (n, r), xi, yi in zip(rs, x, y):
                ax.annotate("%d^3\n%s s" % (n, r["wall_s"]), (xi, yi), fontsize=7, textcoords="offset points",
                            xytext=(4, 4))
            old = sorted((r for r in legacy if r["model"] == model), key=lambda r: int(r["cells"]))
            if old:
                ax.plot([int(r["cells"]) ** 3 * int(r["steps"]) for r in old], [num(r[old_key]) for r in old],
                        mark, color="C%d" % n_model, alpha=0.3, mfc="none", label=name + ", approximate projection")
        if ref is not None:
            ax.axhline(ref, color="grey", lw=0.8, ls=":")
            if ref_label:
                ax.text(ax.get_xlim()[0], ref, " " + ref_label, fontsize=7, va="bottom", color="grey")
        ax.set_xscale("log")
        ax.set_xlabel("cost: cell-steps to t = 0.5 s")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes.flat[0].legend(fontsize=7)
    fig.suptitle("Falling block, mu_S = 1000 Pa: measures against cost (wall time and grid at each point)")
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    cols = ["steps", "wall_s", "ranks"] + [p[0] for p in PANELS]
    print("| model | grid | " + " | ".join(cols) + " |")
    print("|---" * (2 + len(cols)) + "|")
    for model, _, _ in MODELS:
        for n, r in got.get(model, []):
            print("| %s | %d^3 | %s |" % (model, n, " | ".join(r.get(c) or "-" for c in cols)))
    print("wrote", a.output)


if __name__ == "__main__":
    main()
