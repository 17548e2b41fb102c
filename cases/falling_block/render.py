#!/usr/bin/python3
"""Renders the falling block's surface psi = 0 shaded by log10(S2), like the paper's Figs. 1-2:
one row per run (mu_S), one column per time (python/voigt_post/picture.py, which this wraps;
VTK, headless under xvfb-run).

    cases/falling_block/render.py -o blocks.png --times 0.04 0.08 0.12 \\
        --run output/fb_1000 "mu_S = 1000 Pa" --run output/fb_5000 "mu_S = 5000 Pa" [--title TEXT]

The cylinder comes from each run's scene record (scene.yaml); a run from before 2026-12-02 has
none and gets `--cylinder X Y R` (default: the 4.5 cm cylinder of those runs).
"""
import sys

from voigt_post import picture
from voigt_post.scene_record import LEGACY_CYLINDER

if __name__ == "__main__":
    argv = sys.argv[1:]
    cyl = LEGACY_CYLINDER
    if "--cylinder" in argv:
        i = argv.index("--cylinder")
        cyl = tuple(float(v) for v in argv[i + 1:i + 4])
        del argv[i:i + 4]
    legacy = {"obstacles": [{"type": "cylinder", "axis": "z", "center": [cyl[0], cyl[1], 0], "radius": cyl[2]}]}
    picture.main(argv, legacy_obstacles=legacy)
