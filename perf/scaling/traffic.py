#!/usr/bin/python3
"""What a step sends through MPI, per rank, counted by the code (summary.json "mpi", the PMPI
wrappers of src/core/mpi_traffic.cpp), at 1 to 64 ranks oversubscribed on this machine: counts
are exact whatever the cores, times are not. Per stage and kind (point to point: halos and
Tpetra's messages; all to all: the fast diagonalization's transposes; collective: reductions),
rank 0's and the most over the ranks, per step = (run of 1 + N steps - run of 1 step) / N.
Also the one-rank seconds per step and stage at three grid sizes (the per-core rates the
model needs, perf/scaling/model.py).

    perf/scaling/traffic.py [--quick] [--out DIR]     # writes DIR/traffic.csv, DIR/rates.csv
    perf/scaling/traffic.py --no-rates                # the counts only
    perf/scaling/traffic.py --rates 96,128            # more one-rank rates, appended

Budget: full about 20 min on 2 busy cores (64 ranks of a 48^3 grid are the slow runs);
--quick 24^3 and 1-16 ranks, 3 min.
"""
import argparse
import os
import subprocess
import sys
import tempfile

from scaling_common import HERE, NICE, ROOT, SCENES, VOIGT, log, write_csv  # noqa: E402
from voigt_post import launch, series  # noqa: E402

SCENES = dict(SCENES, dam_break=os.path.join(ROOT, "perf", "scenes", "dam_break.yaml"))
# The variants: the defaults (exact operator, fast diagonalization) and multigrid on the same
# operator; the dam break at its own dt rule (its scene fixes dt for perf/compare).
VARIANTS = {
    "fd": ["projection.operator=exact", "projection.preconditioner=fast_diagonalization"],
    "mg": ["projection.operator=exact", "projection.preconditioner=multigrid"],
}
SCENE_SETS = {"falling_block": ["probes=[]"], "dam_break": ["time.dt=0"]}
KINDS = ["point_to_point", "all_to_all", "collective"]


def run(scene, n, ranks, steps, variant, out):
    sets = ["domain.cells=[%d,%d,%d]" % (n, n, n), "output.enabled=false"] + SCENE_SETS[scene] + VARIANTS[variant]
    cmd = launch.voigt_cmd(VOIGT, SCENES[scene], out, sets, ranks=ranks, steps=steps)
    p = subprocess.run(NICE + cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr[-2000:]))
    return series.summary(out)


def flat(j):
    d = {"its": j["poisson"]["iterations_mean"] * j["poisson"]["solves"], "wall": j["wall_seconds"],
         "poisson_setup": j["poisson"].get("setup_seconds", 0), "poisson_solve": j["poisson"].get("solve_seconds", 0)}
    for stage, kinds in list(j["mpi"]["per_stage"].items()) + [("total", j["mpi"]["total"])]:
        for k in KINDS:
            for q in ("messages", "bytes", "messages_max", "bytes_max"):
                d["%s:%s:%s" % (stage, k, q)] = kinds[k][q]
    for stage, s in j["wall_seconds_per_stage"].items():
        d["seconds:" + stage] = s
    return d


def per_step(scene, n, ranks, variant, steps, tmp):
    a = flat(run(scene, n, ranks, 1, variant, os.path.join(tmp, "a")))
    jb = run(scene, n, ranks, 1 + steps, variant, os.path.join(tmp, "b"))
    b = flat(jb)
    row = {k: (b.get(k, 0) - a.get(k, 0)) / steps for k in sorted(set(a) | set(b))}
    row.update(scene=scene, n=n, ranks=ranks, variant=variant,
               fd_ranks="x".join(map(str, jb["poisson"].get("fast_diagonalization_ranks", [0, 0]))))
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out", default=None)
    ap.add_argument("--rates", default=None, help="only the one-rank rates at these n (comma-separated), "
                    "appended to DIR/rates.csv")
    ap.add_argument("--no-rates", action="store_true", help="only the counts (DIR/traffic.csv)")
    a = ap.parse_args()
    out = a.out or os.path.join(HERE, "quick" if a.quick else "results")
    os.makedirs(out, exist_ok=True)
    n, ranks, steps = (24, [1, 2, 4, 8, 16], 2) if a.quick else (48, [1, 2, 4, 8, 16, 32, 64], 3)
    rate_ns = [16, 24, 32] if a.quick else [32, 48, 64]
    rows, rates = [], []
    if a.rates:
        path = os.path.join(out, "rates.csv")
        rates = series.read_csv(path) if os.path.exists(path) else []
        with tempfile.TemporaryDirectory() as tmp:
            for m in [int(x) for x in a.rates.split(",")]:
                for scene in ("falling_block", "dam_break"):
                    for variant in ("fd", "mg"):
                        log(scene, variant, "%d^3" % m, "1 rank (rates)")
                        rates.append(per_step(scene, m, 1, variant, steps, tmp))
                        write_csv(path, rates)
        return
    with tempfile.TemporaryDirectory() as tmp:
        for scene in ("falling_block", "dam_break"):
            for variant in ("fd", "mg"):
                for p in ranks:
                    if variant == "mg" and p not in (1, 8, 64, 16):
                        continue  # multigrid's counts at a few rank counts
                    log(scene, variant, "%d^3" % n, p, "ranks")
                    rows.append(per_step(scene, n, p, variant, steps, tmp))
                for m in [] if a.no_rates else rate_ns:
                    log(scene, variant, "%d^3" % m, "1 rank (rates)")
                    rates.append(per_step(scene, m, 1, variant, steps, tmp))
    write_csv(os.path.join(out, "traffic.csv"), rows)
    if not a.no_rates:
        write_csv(os.path.join(out, "rates.csv"), rates)


if __name__ == "__main__":
    sys.exit(main())
