#!/usr/bin/env python3
"""Two spheres colliding head-on (cases/sphere_collision): restitution and minimum gap.

  collision.py RUN [RUN ...] [--png FILE] [--table]

For each run directory (voigt run output), from the distance d between the centroids averaged
over T = 10 ms (the spheres' elastic vibration, excited by the impulsive start, has about that
period and would otherwise decide the numbers): the impact speed v_in = (d(t1 - T) - d(t1)) / T,
t1 the time the gap between the surfaces first falls below 0.4 R = 2 mm (a distance the coarsest
grid resolves), the rebound speed v_out = the largest opening speed (d(t + T/2) - d(t - T/2)) / T
after that averaged speed turns from closing to opening, e = v_out / v_in, the minimum gap between the two zero levels (solid_gap_left_right,
kernels/contact.hpp) in mm and in cells, and the largest volume drift of either body.
R and the cell size h come from the run's scene record (scene.yaml: the first level set's
sphere, the domain's x extent over its cells).
"""
import argparse
import csv
import os

from voigt_post import scene_record


def analyse(run):
    with open(os.path.join(run, "timeseries.csv")) as f:
        rows = list(csv.DictReader(f))
    t = [float(r["t"]) for r in rows]
    rel = [float(r["solid_left_vx"]) - float(r["solid_right_vx"]) for r in rows]  # > 0: closing
    gap = [float(r["solid_gap_left_right"]) for r in rows]
    scene = scene_record.require(run, "collision.py")
    h = scene_record.spacing(scene)[0]
    R = float(scene_record.level_set(scene)["shape"]["radius"])
    drift = max(abs(float(r[c])) for r in rows for c in ("volume_drift_left", "volume_drift_right"))
    d = [float(r["solid_right_cx"]) - float(r["solid_left_cx"]) for r in rows]
    T = 0.010

    def dist(x):  # d at time x, linear between rows
        i = min(max(1, next((q for q in range(len(t)) if t[q] >= x), len(t) - 1)), len(t) - 1)
        w = (x - t[i - 1]) / (t[i] - t[i - 1])
        return d[i - 1] + w * (d[i] - d[i - 1])

    near = 0.4 * R   # 2 mm: a distance the coarsest grid resolves
    j = next(i for i in range(1, len(gap)) if gap[i] < near)
    t1 = t[j - 1] + (gap[j - 1] - near) / (gap[j - 1] - gap[j]) * (t[j] - t[j - 1])
    v_in = (dist(t1 - T) - dist(t1)) / T
    vbar = [(dist(x - T / 2) - dist(x + T / 2)) / T for x in t]  # closing speed, averaged over T
    ok = [q for q in range(len(t)) if T / 2 <= t[q] <= t[-1] - T / 2]
    c = next(q for q in ok if t[q] > t1 and vbar[q] < 0)  # the rebound starts
    v_out = max(-vbar[q] for q in ok if q >= c)
    k = min(range(j, min(len(t), c + 1)), key=lambda i: gap[i])  # the smallest gap of the collision
    return {"run": run, "h": h, "R_cells": R / h, "v_in": v_in, "v_out": v_out, "e": v_out / v_in,
            "gap_min": gap[k], "gap_cells": gap[k] / h, "t_gap": t[k], "drift": drift, "t": t, "rel": rel, "gap": gap}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--png")
    a = ap.parse_args()
    res = [analyse(r) for r in a.runs]
    print("| R / h | v_in (m/s) | v_out (m/s) | e | min gap (mm) | min gap / h | at t (s) | volume drift |")
    print("|---|---|---|---|---|---|---|---|")
    for r in res:
        print(f"| {r['R_cells']:.0f} | {r['v_in']:.4f} | {r['v_out']:.4f} | {r['e']:.3f} | {1e3 * r['gap_min']:.3f} | "
              f"{r['gap_cells']:.2f} | {r['t_gap']:.4f} | {r['drift']:.1e} |")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(10, 3.8))
        for r in res:
            lab = f"R = {r['R_cells']:.0f} h"
            ax[0].plot(r["t"], [1e3 * g for g in r["gap"]], label=lab)
            ax[1].plot(r["t"], r["rel"], label=lab)
        ax[0].set_ylim(0, 6)  # before the two bands meet the gap reads as the domain's diagonal
        ax[0].set_xlabel("t (s)"), ax[0].set_ylabel("gap between the zero levels (mm)")
        ax[1].set_xlabel("t (s)"), ax[1].set_ylabel("closing speed v_left - v_right (m/s)")
        ax[1].axhline(0, color="k", lw=0.5)
        for x in ax:
            x.legend()
        fig.suptitle("Two soft spheres colliding head-on in a liquid (two level sets)")
        fig.tight_layout()
        fig.savefig(a.png, dpi=110)


if __name__ == "__main__":
    main()
