#!/usr/bin/python3
"""Where the porous bed's gas is fast, and what pushes it: speeds and pressure accelerations
binned by the signed distance to the solid surface, in cells (NOTEBOOK.md, "Why the time step
falls"). Python 3 + numpy + h5py (Debian python3-*).

    cases/porous_bed/band_speeds.py FILE [--packing cases/porous_bed/packing.csv]

FILE: a checkpoint (checkpoint_*.h5) or an output (fields_*.h5) of porous_bed.yaml, or of the
rigid bed (rigid_bed.py), which has no psi: the distance to the packing's spheres stands in.
Only the bed's interior counts (x, z 1.1-9.9 cm, inside the held wall layer; y 6-30 cm).
Node values: velocity as stored; psi, density the mean of the 8 cells around the node (an output
file has no density: it is blended from psi as the model does, with the scene's gas and bed
densities and smoothing); the pressure gradient the semi-staggered one (the mean of the 4
cell-pair differences across each axis). Arrays are stored (z, y, x).
The grid, densities and smoothing come from the scene record in FILE's folder (the run's
output); a file copied out of its run folder is read as the case's porous_bed.yaml (the
paper's grid), with a note on stderr.
"""
import argparse
import csv
import os

import h5py
import numpy as np

from voigt_post import formulas, scene_record, series

HERE = os.path.dirname(os.path.realpath(__file__))


def parameters(path):
    """(origin x y z, h, gas density, bed density, kappa in cells) of the run FILE belongs to;
    the rigid bed (rigid_bed.py: no level set) has no bed density and no kappa (None)."""
    run = os.path.dirname(os.path.abspath(path))
    sc = scene_record.scene_or(run, os.path.join(HERE, "porous_bed.yaml"), "band_speeds.py")
    lo, _ = scene_record.extent(sc)
    ls = sc.get("level_set")
    if not ls:
        return lo, scene_record.spacing(sc)[0], float(scene_record.material(sc)["density"]), None, None
    # kappa: what the run used (summary.json), else the scene's, else Voigt's default (2 cells).
    kappa = series.summary(run, {}).get("level_set", {}).get("smoothing_cells", ls.get("smoothing", 2))
    return (lo, scene_record.spacing(sc)[0], float(scene_record.material(sc)["density"]),
            float(scene_record.material(sc, ls["phase"])["density"]), float(kappa))


def read(f, name):
    for key in ("fields/" + name, name):
        if key in f:
            return np.array(f[key])
    return None


def to_nodes(a):
    n = np.full(tuple(s + 1 for s in a.shape), np.nan)
    n[1:-1, 1:-1, 1:-1] = sum(a[i:i + a.shape[0] - 1, j:j + a.shape[1] - 1, k:k + a.shape[2] - 1]
                              for i in (0, 1) for j in (0, 1) for k in (0, 1)) / 8
    return n


def pressure_gradient(p, h):
    """Node gradient (x, y, z components) of the cell pressure p[z, y, x]."""
    g = np.full(tuple(s + 1 for s in p.shape) + (3,), np.nan)
    gz = (p[1:] - p[:-1]) / h
    gy = (p[:, 1:] - p[:, :-1]) / h
    gx = (p[:, :, 1:] - p[:, :, :-1]) / h
    g[1:-1, 1:-1, 1:-1, 0] = (gx[:-1, :-1] + gx[1:, :-1] + gx[:-1, 1:] + gx[1:, 1:]) / 4
    g[1:-1, 1:-1, 1:-1, 1] = (gy[:-1, :, :-1] + gy[1:, :, :-1] + gy[:-1, :, 1:] + gy[1:, :, 1:]) / 4
    g[1:-1, 1:-1, 1:-1, 2] = (gz[:, :-1, :-1] + gz[:, 1:, :-1] + gz[:, :-1, 1:] + gz[:, 1:, 1:]) / 4
    return g


def sphere_distance(shape, lo, h, packing):
    """max over spheres of r - |x - c| at the nodes (> 0 inside), arrays (z, y, x); LO the
    origin (x y z)."""
    z, y, x = (o + np.arange(n) * h for o, n in zip(lo[::-1], shape))
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    d = np.full(shape, -1e9)
    with open(packing) as f:
        for r in csv.DictReader(f):
            cx, cy, cz, rr = (float(r[k]) for k in "xyzr")
            d = np.maximum(d, rr - np.sqrt((X - cx) ** 2 + (Y - cy) ** 2 + (Z - cz) ** 2))
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("file")
    ap.add_argument("--packing", default=os.path.join(HERE, "packing.csv"))
    a = ap.parse_args()
    lo, h, rho_gas, rho_bed, kappa = parameters(a.file)
    with h5py.File(a.file, "r") as f:
        u, p, psi, rho = (read(f, n) for n in ("velocity", "pressure", "psi", "density"))
    speed = np.sqrt((u ** 2).sum(-1))
    dist = to_nodes(psi) if psi is not None else sphere_distance(speed.shape, lo, h, a.packing)
    dist = dist / h
    if rho is None and psi is not None:  # an output file: the model's blend (Eq. 2, Eq. 4 h)
        rho = rho_gas + (rho_bed - rho_gas) * formulas.heaviside(psi, kappa * h)
    rho_n = to_nodes(rho) if rho is not None else np.full(speed.shape, rho_gas)  # the rigid bed: gas only
    g = pressure_gradient(p, h)
    gmag = np.sqrt((g ** 2).sum(-1))
    z, y, x = np.meshgrid(*(o + np.arange(n) * h for o, n in zip(lo[::-1], speed.shape)), indexing="ij")
    bed = (x > 0.011) & (x < 0.099) & (z > 0.011) & (z < 0.099) & (y > 0.06) & (y < 0.30) & np.isfinite(gmag)
    if psi is None:
        bed &= dist < 0  # inside an obstacle the velocity is held at 0
    print(f"{a.file}: bed interior, {bed.sum()} nodes; max speed {speed[bed].max():.3g} m/s\n")
    print("| distance to the surface (cells) | nodes | mean speed (m/s) | 99th pct | max | median abs(grad p) (Pa/m) | median abs(grad p) / rho (m/s^2) |")
    print("|---|---|---|---|---|---|---|")
    for lo, hi in ((-np.inf, -2), (-2, -1), (-1, 0), (0, 1), (1, np.inf)):
        m = bed & (dist > lo) & (dist <= hi)
        if m.sum() == 0:
            continue
        print(f"| ({lo:g}, {hi:g}] | {m.sum()} | {speed[m].mean():.3g} | {np.percentile(speed[m], 99):.3g} | "
              f"{speed[m].max():.3g} | {np.median(gmag[m]):.4g} | {np.median(gmag[m] / rho_n[m]):.4g} |")
    idx = np.argsort(np.where(bed, speed, -1).ravel())[::-1][:1000]
    along = -(g.reshape(-1, 3)[idx] * u.reshape(-1, 3)[idx]).sum(-1) / speed.ravel()[idx] / rho_n.ravel()[idx]
    print(f"\nThe 1000 fastest nodes (>= {speed.ravel()[idx[-1]]:.3g} m/s): median distance "
          f"{np.median(dist.ravel()[idx]):+.2f} cells, median rho {np.median(rho_n.ravel()[idx]):.3g} kg/m^3, "
          f"median -grad p . u / (rho |u|) {np.median(along):.4g} m/s^2 (> 0: the pressure drives them)")


if __name__ == "__main__":
    main()
