#!/usr/bin/python3
"""The rigid-bed limit of porous_bed.yaml: the same duct, gas, inflow, gravity, wall layer and
projection, with the packing's spheres as fixed obstacles (zero velocity at the nodes inside;
no level set, no smoothing band, no elastic stress). Writes the scene to stdout.
Python 3 + PyYAML (Debian python3-yaml).

    cases/porous_bed/rigid_bed.py [--approximate] > /tmp/rigid_bed.yaml
    build/voigt run /tmp/rigid_bed.yaml -o OUT --set time.end=0.05 --set output.interval=0.025
    cases/porous_bed/band_speeds.py OUT/fields_000002.h5

--approximate: the 7-point approximate projection with multigrid at 1e-6 (the scene's settings
before 2026-12-05) instead of the scene's exact one, whose fast-diagonalization preconditioner
(the open box's inverse) needs 119-173 CG iterations a step with the spheres fixed (README.md,
"The rigid-bed limit"). The study's rigid-bed rows (results.csv, run ids rigid_<grid>) use it.
"""
import argparse
import csv
import os
import sys

import yaml

ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
ap.add_argument("--approximate", action="store_true", help="approximate projection, multigrid at 1e-6")
args = ap.parse_args()
here = os.path.dirname(os.path.realpath(__file__))
with open(os.path.join(here, "porous_bed.yaml")) as f:
    scene = yaml.safe_load(f)
scene["name"] = "rigid_bed"
scene["effects"] = [e for e in scene["effects"] if e in ("navier_stokes", "gravity", "obstacles")]
for key in ("level_set", "reinit", "elasticity", "solid_body"):
    scene.pop(key, None)
scene["materials"] = {scene["fluid"]: scene["materials"][scene["fluid"]]}
with open(os.path.join(here, "packing.csv")) as f:
    for r in csv.DictReader(f):
        scene["obstacles"].append({"type": "sphere", "center": [float(r[k]) for k in "xyz"], "radius": float(r["r"])})
scene["output"]["fields"] = ["velocity", "pressure"]
for probe in scene.get("probes", []):
    probe["fields"] = [x for x in probe["fields"] if x != "psi"]
if args.approximate:  # porous_bed.yaml's projection until 2026-12-05 (its git history)
    scene["projection"] = {"operator": "approximate", "preconditioner": "multigrid", "tolerance": 1.0e-6,
                           "multigrid_reuse": "RAP", "multigrid_refresh": 10, "multigrid_smoother": "chebyshev",
                           "chebyshev_degree": 1}
sys.stdout.write("# Written by cases/porous_bed/rigid_bed.py from porous_bed.yaml and packing.csv: the rigid-bed limit.\n")
yaml.safe_dump(scene, sys.stdout, default_flow_style=None, sort_keys=False)
