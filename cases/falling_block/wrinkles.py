#!/usr/bin/env python3
"""The block's face shapes from a falling_block run's psi output (numpy + h5py): are the
surface's wrinkles a resolved deformation of the block or a grid-scale defect?

For every fields_*.h5 with psi: the heights of the top and bottom faces' zero crossings (y is
vertical) over the columns within WINDOW/2 of the block's footprint centre, less a quadratic fit
in x and z (the global bending over the cylinder), split into the mid-surface (bending) and the
half-thickness. Reported in mm and in cells, with the shares of the top face's departure power
at wavelengths below 3 cells (grid scale) and in bands of wavelength in mm.
A grid-scale defect keeps its size in cells as h shrinks; a resolved deformation keeps its size
in mm and its wavelengths in mm.

    cases/falling_block/wrinkles.py RUN_DIR [RUN_DIR ...] [--window 0.045] > wrinkles.csv
"""
import argparse
import glob
import os

import h5py
import numpy as np


def faces(psi):
    """Top and bottom zero crossings per (axis 0, axis 2) column, in cell units (cell centres at j + 1/2)."""
    n0, ny, n2 = psi.shape
    top = np.full((n0, n2), np.nan)
    bot = top.copy()
    for i in range(n0):
        for k in range(n2):
            c = psi[i, :, k]
            w = np.where(c > 0)[0]
            if len(w) == 0 or w.max() + 1 >= ny or w.min() == 0:
                continue
            j = w.max()
            top[i, k] = j + 0.5 + c[j] / (c[j] - c[j + 1])
            j = w.min()
            bot[i, k] = j + 0.5 - c[j] / (c[j] - c[j - 1])
    return top, bot


def detrend(m):
    """m less its least-squares quadratic in the two column indices."""
    a, b = np.meshgrid(*[np.arange(n, dtype=float) for n in m.shape], indexing="ij")
    A = np.stack([np.ones_like(a), a, b, a * a, b * b, a * b], -1).reshape(-1, 6)
    return m - (A @ np.linalg.lstsq(A, m.ravel(), rcond=None)[0]).reshape(m.shape)


BANDS_MM = (5, 10, 20)  # wavelength band edges of the spectrum, mm


def power_split(d, h):
    """Shares of d's spectral power at wavelengths below 3 cells, then in the bands of BANDS_MM."""
    k0, k1 = (np.fft.fftfreq(n) for n in d.shape)  # cycles per cell
    kk = np.hypot(k0[:, None], k1[None, :])
    P = np.abs(np.fft.fft2(d)) ** 2
    tot = P[kk > 0].sum()
    lam = np.where(kk > 0, h * 1e3 / np.where(kk > 0, kk, 1), np.inf)  # wavelength, mm
    edges = (0,) + BANDS_MM + (np.inf,)
    bands = [P[(kk > 0) & (lam >= a) & (lam < b)].sum() / tot for a, b in zip(edges[:-1], edges[1:])]
    return [P[kk > 1 / 3].sum() / tot] + bands


def analyse(run, window):
    rows = []
    for path in sorted(glob.glob(os.path.join(run, "fields_*.h5"))):
        with h5py.File(path, "r") as f:
            if "psi" not in f:
                continue
            psi = f["psi"][...]
            t = float(f.attrs.get("time", np.nan))
        h = 0.1 / psi.shape[1]
        top, bot = faces(psi)
        cols = np.argwhere(np.isfinite(top) & np.isfinite(bot))
        c0, c2 = cols.mean(0)
        half = window / 2 / h
        s0 = slice(int(np.ceil(c0 - half)), int(np.floor(c0 + half)) + 1)
        s2 = slice(int(np.ceil(c2 - half)), int(np.floor(c2 + half)) + 1)
        T, B = top[s0, s2], bot[s0, s2]
        if not (np.isfinite(T).all() and np.isfinite(B).all()):
            continue  # the window leaves the block (it has slid off the cylinder)
        T, B = detrend(T), detrend(B)
        bend, thick = (T + B) / 2, (T - B) / 2
        rows.append([run, psi.shape[1], t, T.std() * h * 1e3, B.std() * h * 1e3, bend.std() * h * 1e3,
                     thick.std() * h * 1e3, T.std(), B.std()] + power_split(T, h))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--window", type=float, default=0.045, help="square of columns analysed, m (default 0.045)")
    args = ap.parse_args()
    edges = ("0",) + tuple(map(str, BANDS_MM)) + ("inf",)
    bands = ",".join("top_power_%s_%s_mm" % ab for ab in zip(edges[:-1], edges[1:]))
    print("run,cells,t,top_mm,bottom_mm,bending_mm,thickness_mm,top_cells,bottom_cells,top_power_below_3_cells," + bands)
    for run in args.runs:
        for r in analyse(run, args.window):
            print("%s,%d,%.3f" % tuple(r[:3]) + "".join(",%.3f" % v for v in r[3:]))


if __name__ == "__main__":
    main()
