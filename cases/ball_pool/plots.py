#!/usr/bin/env python3
"""cases/ball_pool: the ball and the water on the mid-plane, and the ball's speed against depth.

  plots.py RUN [--tank TANK_RUN] [--no-hide NO_HIDE_RUN] -o ball_pool.png

RUN: `voigt run cases/ball_pool/ball_pool.yaml` output (fields every 0.05 s). TANK_RUN: the
walk-through's one-level-set scene (a full tank) with the ball started at the same height;
NO_HIDE_RUN: a run without the extension of the water under the ball (for the README's figure).
The tank, the water's depth and the ball's radius come from RUN's scene record (scene.yaml).
"""
import argparse
import csv
import glob
import os

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from voigt_post import scene_record  # noqa: E402


def series(run, prefix):
    rows = list(csv.DictReader(open(os.path.join(run, "timeseries.csv"))))
    return np.array([[float(r["t"]), float(r[prefix + "cy"]), float(r[prefix + "vy"])] for r in rows])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("--tank")
    ap.add_argument("--no-hide")
    ap.add_argument("-o", "--out", default="ball_pool.png")
    a = ap.parse_args()
    scene = scene_record.require(a.run, "plots.py")
    lo, hi = scene_record.extent(scene)
    surface = float(scene_record.level_set(scene, "pool")["shape"]["hi"][1])   # the water's top (m)
    radius = float(scene_record.level_set(scene, "ball")["shape"]["radius"])   # centroid at floor contact
    files = sorted(glob.glob(os.path.join(a.run, "fields_*.h5")))
    picks = [0, 2, 3, 4, len(files) - 1]
    fig, ax = plt.subplots(1, len(picks) + 1, figsize=(3.0 * (len(picks) + 1), 3.6),
                           gridspec_kw={"width_ratios": [1] * len(picks) + [1.6]})
    for p, f in zip(ax, [files[i] for i in picks]):
        h = h5py.File(f, "r")
        pool, ball = np.array(h["psi_pool"]), np.array(h["psi_ball"])
        t = float(h.attrs["time"])
        k = pool.shape[2] // 2
        nx, ny = pool.shape[0], pool.shape[1]
        x = lo[0] + (np.arange(nx) + 0.5) * (hi[0] - lo[0]) / nx
        y = lo[1] + (np.arange(ny) + 0.5) * (hi[1] - lo[1]) / ny
        water = (pool[:, :, k] > 0) & (ball[:, :, k] <= 0)
        p.contourf(x * 100, y * 100, water.T.astype(float), levels=[0.5, 1.5], colors=["#9cc9f0"])
        p.contour(x * 100, y * 100, pool[:, :, k].T, levels=[0], colors="#1f5fa8", linewidths=1)
        p.contour(x * 100, y * 100, ball[:, :, k].T, levels=[0], colors="#d0621b", linewidths=1.5)
        p.set_aspect("equal")
        p.set_title(f"t = {t:.2f} s")
        p.set_xlabel("x (cm)")
    ax[0].set_ylabel("y (cm)")
    q = ax[-1]
    s = series(a.run, "solid_ball_")
    q.plot(s[:, 1] * 100, -s[:, 2], label="ball dropped into the pool (two level sets)")
    if a.tank:
        s2 = series(a.tank, "solid_")
        q.plot(s2[:, 1] * 100, -s2[:, 2], label="same ball from rest in a full tank (one level set)")
    if a.no_hide:
        s3 = series(a.no_hide, "solid_ball_")
        q.plot(s3[:, 1] * 100, -s3[:, 2], ":", label="pool, water not extended under the ball")
    q.axvline(surface * 100, color="#1f5fa8", lw=0.6)
    q.axvline((lo[1] + radius) * 100, color="k", lw=0.6)
    q.set_xlim(7, 0)
    q.set_xlabel("ball centroid height (cm): water surface %.1f, floor contact %.1f" % (surface * 100,
                                                                                      (lo[1] + radius) * 100))
    q.set_ylabel("sinking speed (m/s)")
    q.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main()
