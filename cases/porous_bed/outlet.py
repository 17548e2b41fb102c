#!/usr/bin/python3
"""What the outlet does in porous-bed runs: per field output, the fastest gas anywhere, the
fastest at the outlet plane (y = 0.33 m) and the fraction of its free nodes with backflow
(v_y < 0); per run, its steps and what the paper reports at its end (section gradient over
y = 0.10-0.25 m, centroid rise). README.md, "The outlet". Python 3 + numpy + h5py.

    cases/porous_bed/outlet.py RUN_DIR [RUN_DIR ...]

The scene's outlet is p = 0 with a free velocity (`outflow`); the paper's "drawn from the top
at an equal mass flow rate" also reads as a prescribed uniform 0.1 m/s there:
    --set 'boundaries.y+={type: inflow, velocity: [0, 0.1, 0]}'
"""
import json
import os
import sys

import numpy as np

from voigt_post import fields
from voigt_post.porous_bed import RunDir
from voigt_post.xdmf import frames


def outlet_stats(u):
    """(max |u|, max |u| on the last y plane, fraction of that plane's free nodes with u_y < 0)
    of a node velocity array stored (z, y, x, 3), components (x, y, z). The plane's edge nodes
    lie on the no-slip side walls (u = 0): not counted."""
    speed = np.sqrt((u ** 2).sum(axis=-1))
    top = u[1:-1, -1, 1:-1, :]
    return float(speed.max()), float(speed[:, -1, :].max()), float((top[..., 1] < 0).mean())


def run_row(d):
    r = RunDir(d)
    with open(os.path.join(d, "summary.json")) as f:
        steps = json.load(f)["steps"]
    _, grad = r.section_gradient()
    t, cy = r.centroid()
    per_output = [(f[0],) + outlet_stats(fields.read(f[1], "velocity")) for f in frames(d)]
    return steps, grad, 1e3 * (cy[-1] - cy[0]), per_output


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for d in sys.argv[1:]:
        steps, grad, rise, per = run_row(d)
        print("%s: %d steps, section gradient %.1f Pa/m, centroid rise %.2f mm" % (os.path.basename(os.path.normpath(d)),
                                                                                   steps, grad, rise))
        print("  per output: t (s): max |u| / outlet max |u| (m/s) / outlet backflow fraction")
        print("  " + " ".join("%.2g: %.1f/%.1f/%.2f" % s for s in per))


if __name__ == "__main__":
    main()
