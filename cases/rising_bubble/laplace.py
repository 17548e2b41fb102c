#!/usr/bin/python3
"""The Laplace jump of a static-drop run (static_drop.yaml or any drop scene with output of
pressure and psi): the mean pressure beyond 4 cells inside (psi > 4 h) minus that beyond 4
cells outside, from the last fields file, against sigma / R (2-D: an axis of at most 2 cells)
or 2 sigma / R (3-D), R the scene's sphere or cylinder radius, else from the drop's volume
(level_set's volume_<phase> in timeseries.csv, which the smoothed Heaviside makes 0.2 % large).

    laplace.py DIR [--check TOL]      print the jump; --check: exit 1 unless within TOL (relative)
"""
import argparse
import csv
import glob
import math
import os
import sys

import h5py
import numpy as np

from voigt_post import scene_record


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dir")
    ap.add_argument("--check", type=float)
    a = ap.parse_args()
    scene = scene_record.require(a.dir, "laplace.py")
    sigma = float(scene["surface_tension"]["sigma"])
    phase = scene_record.level_set(scene)["phase"]
    cells, (lo, hi) = scene["domain"]["cells"], scene_record.extent(scene)
    h = min(scene_record.spacing(scene))
    flat = [d for d in range(3) if cells[d] <= 2]
    rows = list(csv.DictReader(open(os.path.join(a.dir, "timeseries.csv"))))
    volume = float(rows[-1]["volume_" + phase])
    shape = scene_record.level_set(scene).get("shape", {})
    if shape.get("type") in ("sphere", "cylinder"):
        R, src = float(shape["radius"]), "the scene's"
    elif flat:
        R, src = math.sqrt(volume / (hi[flat[0]] - lo[flat[0]]) / math.pi), "from the volume"
    else:
        R, src = (3 * volume / (4 * math.pi)) ** (1 / 3), "from the volume"
    laplace = (1 if flat else 2) * sigma / R
    f = h5py.File(sorted(glob.glob(os.path.join(a.dir, "fields_*.h5")))[-1], "r")
    p, psi = np.asarray(f["pressure"]), np.asarray(f["psi"])
    jump = p[psi > 4 * h].mean() - p[psi < -4 * h].mean()
    err = jump / laplace - 1
    print("jump %.5f, Laplace %.5f (R = %.5f, %s), error %+.3f %%" % (jump, laplace, R, src, 100 * err))
    if a.check is not None and abs(err) > a.check:
        print("FAIL: outside %g" % a.check)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
