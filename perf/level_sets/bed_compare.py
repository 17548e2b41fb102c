#!/usr/bin/env python3
"""The porous bed on K level sets against one (perf/level_sets/README.md): for each run folder,
steps, wall time, the section-averaged gradient over y = 0.10-0.25 m at the last field output,
and the bed's centroid rise (with several level sets: the volume-weighted mean of the groups'
centroids) at the end and at its largest.

  bed_compare.py RUN [RUN ...] [--png FILE]     (FILE: the centroid rise against time, each run)
"""
import json
import os
import sys

import numpy as np

from voigt_post import porous_bed as R
from voigt_post import series


def centroid(d):
    cols = series.timeseries(d)
    t = np.array(cols["t"])
    if "solid_cy" in cols:
        return t, np.array(cols["solid_cy"])
    groups = sorted({k[len("solid_"):-len("_cy")] for k in cols if k.startswith("solid_") and k.endswith("_cy")})
    v = np.array([cols["solid_%s_volume" % g] for g in groups])
    y = np.array([cols["solid_%s_cy" % g] for g in groups])
    return t, (v * y).sum(axis=0) / v.sum(axis=0)


def main():
    png = None
    args = sys.argv[1:]
    if "--png" in args:
        i = args.index("--png")
        png = args[i + 1]
        del args[i:i + 2]
    curves = []
    print("| run | level sets | steps | wall (s) | s/step | section gradient (Pa/m) at t | centroid rise (mm) | peak rise (mm) at t |")
    print("|---|---|---|---|---|---|---|---|")
    for d in args:
        s = json.load(open(os.path.join(d, "summary.json")))
        n = len(s["level_sets"]) if "level_sets" in s else 1
        t, cy = centroid(d)
        st, sg = R.RunDir(d).section_gradient()
        pk, pt = R.peak_rise(t, cy)
        print(f"| {os.path.basename(os.path.normpath(d))} | {n} | {s['steps']} | {s['wall_seconds']:.0f} | "
              f"{s['wall_seconds'] / max(1, s['steps_this_run']):.4f} | {sg:.1f} at {st:.2f} | "
              f"{1000 * (cy[-1] - cy[0]):.2f} | {pk:.2f} at {pt:.3f} |")
        curves.append((f"{n} level set{'s' if n > 1 else ''}", t, 1000 * (cy - cy[0])))
    if png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6, 3.6))
        for lab, t, rise in curves:
            ax.plot(t, rise, label=lab)
        ax.set_xlabel("t (s)")
        ax.set_ylabel("bed centroid rise (mm)")
        ax.set_title("Porous bed, half grid, mu_S = 1000 Pa: spheres on K level sets")
        ax.legend()
        fig.tight_layout()
        fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
