#!/usr/bin/env python3
"""The porous bed (cases/porous_bed) with its 181 spheres on K level sets instead of one.

  bed.py K OUTDIR        writes OUTDIR/bed_K.yaml and OUTDIR/cluster_*.csv

The spheres are sorted by height and split into K groups of consecutive layers (nearly equal
counts); each group is one level set (a sphere_packing of its spheres), so spheres within a group
are bonded as in the one-level-set bed (their zero levels join where they overlap) and the groups
touch without merging. K = 181: one level set per sphere. The elastic stress lives on the
union of all of them (elasticity.level_set: the list), which at the start is the one-level-set
bed's psi (max of the spheres' distances). perf/level_sets/README.md has the measurements.
"""
import csv
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
BED = os.path.join(HERE, "..", "..", "cases", "porous_bed")


def main():
    k, out = int(sys.argv[1]), sys.argv[2]
    os.makedirs(out, exist_ok=True)
    rows = list(csv.DictReader(open(os.path.join(BED, "packing.csv"))))
    rows.sort(key=lambda r: (float(r["y"]), float(r["x"]), float(r["z"])))
    n = len(rows)
    names = []
    for g in range(k):
        part = rows[g * n // k:(g + 1) * n // k]
        name = "c%d" % g
        with open(os.path.join(out, "cluster_%d.csv" % g), "w") as f:
            f.write("x,y,z,r\n")
            for r in part:
                f.write("%s,%s,%s,%s\n" % (r["x"], r["y"], r["z"], r["r"]))
        names.append(name)
    scene = open(os.path.join(BED, "porous_bed.yaml")).read()
    entries = "\n".join("  - {name: %s, phase: bed, smoothing: 2, shape: {type: sphere_packing, file: cluster_%d.csv}}"
                        % (nm, g) for g, nm in enumerate(names))
    scene = re.sub(r"\nlevel_set:\n(  .*\n)+", "\nlevel_sets:\n" + entries + "\n", scene)
    scene = scene.replace("elasticity: {}", "elasticity: {level_set: [%s]}" % ", ".join(names))
    scene = re.sub(r"solid_body: \{contacts: false, bending: false\}.*\n",
                   "solid_body: {contacts: false, bending: false, pairs: false, level_set: [%s]}\n" % ", ".join(names), scene)
    scene = scene.replace("name: porous_bed", "name: porous_bed_%d_level_sets" % k)
    scene = re.sub(r"fields: \[psi, ", "fields: [", scene)
    scene = scene.replace("fields: [pressure, psi, velocity]", "fields: [pressure, velocity]")
    open(os.path.join(out, "bed_%d.yaml" % k), "w").write(scene)


if __name__ == "__main__":
    main()
