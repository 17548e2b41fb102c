#!/usr/bin/python3
"""What the paper's grid costs on the porous bed (issue 22 item 4): the section-averaged
pressure gradient and the centroid rise at t = 1 s on the half grid (25 x 75 x 25) and the
paper's (50 x 150 x 50), for each modulus, against the cost of each run. Python 3 + matplotlib.
Reads results.csv (rows mu<MU>_<model><tag>_<grid> with t_end = 1 s), writes a PNG and
prints the table it drew.

    cases/porous_bed/grid_cost.py -o cases/porous_bed/grid_cost.png [--model extend]
        [--tag +global+exact] [--tag +global]

Cost is cell-steps (cells x steps), which does not depend on the machine; each point is
annotated with its wall time (results.csv wall_s; the runs shared a 2-core machine, so wall
times are rough). A modulus with both grids is joined by a line; one with a single grid is
a lone point. Each --tag is one set (the first drawn solid, the others faint).
"""
import argparse
import csv
import os
import re

HERE = os.path.dirname(os.path.realpath(__file__))
GRIDS = ("25x75x25", "50x150x50")
PANELS = (("section_gradient", "section-averaged -dp/dy, y = 0.10-0.25 m (Pa/m)", "paper O(1000) Pa/m"),
          ("centroid_rise_mm", "bed centroid rise at 1 s (mm)", "paper ~10 mm"))


def cells(grid):
    n = 1
    for v in grid.split("x"):
        n *= int(v)
    return n


def finished(r):
    """A row at t = 1 s with the numbers the plot needs."""
    try:
        return abs(float(r["t_end"]) - 1) < 1e-6 and int(r["steps"]) > 0 and all(
            r.get(k) not in (None, "") and float(r[k]) == float(r[k]) for k, _, _ in PANELS)
    except (KeyError, ValueError):
        return False


def sets(path, model, tag):
    """{mu: {grid: row}} of the finished (t_end = 1 s) runs mu<mu>_<model><tag>_<grid>."""
    pat = re.compile(r"mu(\d+)_%s%s_(\d+x\d+x\d+)$" % (re.escape(model), re.escape(tag)))
    out = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            m = pat.match(r["run_id"])
            if m and m.group(2) in GRIDS and finished(r):
                out.setdefault(int(m.group(1)), {})[m.group(2)] = r
    return dict(sorted(out.items()))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--results", default=os.path.join(HERE, "results.csv"))
    ap.add_argument("--model", default="extend")
    ap.add_argument("--tag", action="append", help="run-id tag of a set (default: +global+exact and +global)")
    a = ap.parse_args()
    tags = a.tag or ["+global+exact", "+global"]
    got = [(t, sets(a.results, a.model, t)) for t in tags]
    if not any(s for _, s in got):
        raise SystemExit("grid_cost.py: no finished rows mu<MU>_%s<tag>_<grid> in %s" % (a.model, a.results))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    mus = sorted({mu for _, s in got for mu in s})
    for ax, (key, label, ref) in zip(axes, PANELS):
        for k, (tag, s) in enumerate(got):
            for mu, by_grid in s.items():
                pts = [(cells(g) * int(by_grid[g]["steps"]), float(by_grid[g][key]), by_grid[g]) for g in GRIDS
                       if g in by_grid]
                c = "C%d" % (mus.index(mu) % 10)
                ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-" if k == 0 else "s--", color=c,
                        alpha=1 if k == 0 else 0.35, mfc=None if k == 0 else "none",
                        label="%d Pa %s" % (mu, tag))
                if k == 0:
                    for x, y, r in pts:
                        ax.annotate("%s s" % r["wall_s"], (x, y), fontsize=7, textcoords="offset points",
                                    xytext=(4, 3))
        ax.set_xscale("log")
        ax.set_xlabel("cost: cell-steps to t = 1 s (left: 25 x 75 x 25, right: 50 x 150 x 50)")
        ax.set_ylabel(label)
        ax.set_title(ref, fontsize=8, loc="right", color="grey")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, ncol=2)
    fig.suptitle("Porous bed (%s): the paper's grid against half of it, at t = 1 s; solid: %s, faint: %s"
                 % (a.model, tags[0], ", ".join(tags[1:]) or "-"))
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    cols = ["steps", "wall_s", "ranks", "section_gradient", "centroid_rise_mm"]
    print("| set | mu_S | grid | cell-steps | " + " | ".join(cols) + " |")
    print("|---" * (4 + len(cols)) + "|")
    for tag, s in got:
        for mu, by_grid in s.items():
            for g in GRIDS:
                if g in by_grid:
                    r = by_grid[g]
                    print("| %s | %d | %s | %.3g | %s |" % (tag, mu, g, cells(g) * int(r["steps"]),
                                                           " | ".join(r.get(c) or "-" for c in cols)))
    print("wrote", a.output)


if __name__ == "__main__":
    main()
