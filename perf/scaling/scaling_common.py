"""What the scaling study's parts and tables share (perf/scaling/run.py, scaling_tables.py): paths,
scenes, the halo-field counts of the cost model, CSV files and the log-log fit."""
import math
import os
import time

from voigt_post import launch, series

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = launch.REPO
BUILD = launch.build_dir()
VOIGT = os.path.join(BUILD, "voigt")
PSCALE = os.path.join(BUILD, "perf", "perf_poisson_scaling")
NICE = ["nice", "-n", "5"]
TOP_STAGES = ["properties", "advection", "momentum", "projection", "corrections", "diagnostics"]
NESTED = ["stress", "forces"]  # run inside momentum, once per Runge-Kutta substage
GHOST = 2  # kGhost, src/core/grid.hpp

# Scalar fields exchanged per step (Halo::exchange calls, vector = 3, stress = 6), counted
# from the code (git grep 'halo->exchange\|refresh'):
#   navier_stokes momentum: u in each of 2 RK stages (momentum.cpp)                    6
#   navier_stokes projection: u, dp, p, u (projection.cpp project)                     8
#   navier_stokes refreshCoefficients (density changed: two-phase, every step): rho, coef 4
#   level_set advect: u, psi in each of 2 RK stages, psi after (advect.cpp)             6
#   elasticity advect: u, 6 stresses in each of 2 RK stages, 6 after; update: u        24
#   reinit (iterations 2, volume constraint): psi, then psi1, psiT, psi per iteration   7
#   conservative momentum (advection.momentum auto: phases of different density):
#     node density r0, stage density r1 (momentum.cpp nodeDensity, rk2 stage 1)        2
HALO_FIELDS = {
    "cavity": 6 + 8,
    "two_phase_elastic": 6 + 8 + 4 + 6 + 24 + 7,
}
CONSERVATIVE_FIELDS = 2
SCENES = {
    "cavity": os.path.join(HERE, "cavity.yaml"),
    "falling_block": os.path.join(ROOT, "cases", "falling_block", "falling_block.yaml"),
    "porous_bed": os.path.join(HERE, "porous_bed.yaml"),
}
HALO_KIND = {"cavity": "cavity", "falling_block": "two_phase_elastic", "porous_bed": "two_phase_elastic"}


def log(*a):
    print(time.strftime("%H:%M:%S"), *a, flush=True)


def write_csv(path, rows):
    series.write_csv(path, rows)
    log("wrote", os.path.relpath(path, ROOT))


read_csv = series.read_csv


def fit(ns, ys):
    """Least-squares slope and prefactor of log y = log C + alpha log n."""
    lx = [math.log(n) for n in ns]
    ly = [math.log(max(y, 1e-300)) for y in ys]
    m = len(lx)
    if m < 2:
        return float("nan"), float("nan")
    mx, my = sum(lx) / m, sum(ly) / m
    sxx = sum((x - mx) ** 2 for x in lx)
    alpha = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sxx
    return alpha, math.exp(my - alpha * mx)


def cells_of(s):
    a = [int(x) for x in s.split("x")]
    return a[0] * a[1] * a[2]


def best_rounds(rows):
    """Per (scene, ranks) the round with the smallest wall time per step."""
    best = {}
    for r in rows:
        k = (r["scene"], r["cells"], int(r["ranks"]))
        if k not in best or float(r["wall"]) < float(best[k]["wall"]):
            best[k] = r
    return [best[k] for k in sorted(best, key=lambda k: (k[0], k[2]))]
