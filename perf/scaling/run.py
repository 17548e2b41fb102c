#!/usr/bin/python3
"""Scaling: Poisson iterations against grid size, a whole step split by stage and effect
for the paper's two scenes, MPI strong scaling (1, 2, 4 ranks) with the split into halo
exchange, Poisson solve and kernels, and a cost model for clusters checked against the
measurements. Writes CSVs, tables.md and poisson_iterations.png into the output
directory and (full mode) the tables into README.md between the RESULTS markers.

    perf/scaling/run                  # full (budget: about 18 min on 2 busy cores; README.md)
    perf/scaling/run --quick          # smaller grids, fewer steps (< 10 min); writes
                                      # perf/scaling/quick/, leaves README.md alone
    perf/scaling/run --parts poisson,steps,mpi    # a subset (the model reads their CSVs)

Build directory: $VOIGT_BUILD_DIR (default <repo>/build): voigt and perf/perf_poisson_scaling.
MPI: mpirun --allow-run-as-root --oversubscribe (4 ranks on a 2-core machine are
oversubscribed: their times say how the code behaves when ranks share cores, not how it
scales).

Per-step costs are differences of two runs, 1 step and 1 + N steps, so that the first
step's one-off work (initial pressure solve, multigrid hierarchy, null space) is left out:
per step = (summary(1 + N) - summary(1)) / N, stage by stage.
"""
import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import sys
import time

from voigt_post import launch, report, series
from scaling_common import BUILD, HERE, NICE, PSCALE, ROOT, SCENES, VOIGT, log, write_csv
from scaling_tables import model_tables, mpi_tables, poisson_tables, step_tables

LOADS = []  # 1-minute load average at the start of each voigt run


# ---------------------------------------------------------------- running voigt
def voigt_run(scene, cells, steps, ranks, out, extra=()):
    """voigt run ... --steps; returns (summary dict, max RSS in KB of the (1-rank) process or None)."""
    sets = ["domain.cells=[%s]" % ",".join(map(str, cells)), "output.enabled=false"] + list(extra)
    cmd = NICE + launch.voigt_cmd(VOIGT, SCENES[scene], out, sets, ranks=ranks, steps=steps)
    rss = None
    if ranks == 1:
        cmd = ["/usr/bin/time", "-f", "MAXRSS %M"] + cmd
    LOADS.append(os.getloadavg()[0])
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr[-2000:]))
    m = re.search(r"MAXRSS (\d+)", p.stderr)
    if m:
        rss = int(m.group(1))
    return series.summary(out), rss


def flat(j):
    """The numbers of a summary that the per-step differences need."""
    d = {"wall": j["wall_seconds"], "halo_s": j["halo"]["seconds"], "halo_bytes": j["halo"]["bytes"],
         "halo_messages": j["halo"]["messages"], "poisson_s": j.get("poisson", {}).get("solve_seconds", float("nan")),
         "poisson_its": j.get("poisson", {}).get("iterations_mean", 0) * j.get("poisson", {}).get("solves", 0),
         "sim_time": j["simulated_time"]}
    for k, v in j["wall_seconds_per_stage"].items():
        d["stage:" + k] = v
    for k, v in j["wall_seconds_per_effect"].items():
        d["effect:" + k] = v
    return d


def per_step(scene, cells, n, ranks, tmp, extra=()):
    """Per-step costs from runs of 1 and 1 + n steps; also the summary of the long run."""
    j1, rss1 = voigt_run(scene, cells, 1, ranks, os.path.join(tmp, "a"), extra)
    jn, rssn = voigt_run(scene, cells, 1 + n, ranks, os.path.join(tmp, "b"), extra)
    a, b = flat(j1), flat(jn)
    d = {k: (b.get(k, 0) - a.get(k, 0)) / n for k in set(a) | set(b)}
    d["load"] = LOADS[-1]
    return d, jn, rssn


# ---------------------------------------------------------------- 1. Poisson
def part_poisson(cfg, out):
    rows = []
    for pc in ["sgs", "multigrid"]:
        for op, sizes in [("approximate", cfg["poisson_approx"]), ("exact", cfg["poisson_exact"])]:
            cmd = NICE + [PSCALE, "1e-8", pc] + [str(s) for s in sizes] + ["--operators=" + op,
                                                                            "--step=%d" % cfg["poisson_step"], "--csv"]
            log("poisson:", " ".join(cmd[3:]))
            p = subprocess.run(cmd, capture_output=True, text=True, check=True)
            rows += list(csv.DictReader(p.stdout.splitlines()))
    write_csv(os.path.join(out, "poisson.csv"), rows)


# ---------------------------------------------------------------- 2. step split
def part_steps(cfg, out, tmp):
    rows = []
    _, base = voigt_run("cavity", [8, 8, 8], 1, 1, os.path.join(tmp, "base"))
    for run in cfg["step_runs"]:
        scene, cells, n = run[:3]
        extra = run[3] if len(run) > 3 else []
        log("step split:", scene, cells, "1 +", n, "steps", " ".join(extra))
        t0 = time.time()
        d, j, rss = per_step(scene, cells, n, 1, os.path.join(tmp, "steps"), extra)
        rows.append(dict(scene=scene, cells="x".join(map(str, cells)), steps=n, ranks=1, rss_kb=rss or 0,
                         variant=" ".join(extra),
                         baseline_rss_kb=base or 0,
                         memory_bytes_per_rank=j["memory_bytes_per_rank"],
                         matrix_nonzeros=j.get("poisson", {}).get("matrix_nonzeros", 0),
                         its_mean=j.get("poisson", {}).get("iterations_mean", 0),
                         stress_cells_mean=j.get("elasticity", {}).get("stress_cells_mean", 0),
                         reinit_band_mean=j.get("reinit", {}).get("band_cells_mean", 0),
                         run_seconds=time.time() - t0, **{k: v for k, v in d.items()}))
    write_csv(os.path.join(out, "step_split.csv"), rows)


# ---------------------------------------------------------------- 3. MPI
def part_mpi(cfg, out, tmp):
    rows = []
    for rnd in range(cfg["mpi_rounds"]):
        for scene, cells, n in cfg["mpi_runs"]:
            for ranks in [1, 2, 4]:
                log("mpi round %d:" % rnd, scene, cells, ranks, "ranks, 1 +", n, "steps")
                d, j, rss = per_step(scene, cells, n, ranks, os.path.join(tmp, "mpi"))
                rows.append(dict(round=rnd, scene=scene, cells="x".join(map(str, cells)), steps=n, ranks=ranks,
                                 decomposition="x".join(map(str, j["grid"]["decomposition"])),
                                 memory_bytes_per_rank=j["memory_bytes_per_rank"],
                                 its_mean=j.get("poisson", {}).get("iterations_mean", 0), **d))
    write_csv(os.path.join(out, "mpi.csv"), rows)



CONFIGS = {
    "quick": {
        "poisson_approx": [16, 24, 32, 48], "poisson_exact": [16, 24, 32], "poisson_step": 3,
        "step_runs": [("falling_block", [30, 30, 30], 3), ("porous_bed", [20, 60, 20], 3),
                      ("falling_block", [30, 30, 30], 3, ["projection.preconditioner=sgs"])],
        "mpi_runs": [("cavity", [48, 48, 48], 4), ("falling_block", [32, 32, 32], 3)], "mpi_rounds": 1,
    },
    "full": {
        "poisson_approx": [16, 24, 32, 48, 64, 96], "poisson_exact": [16, 24, 32, 48], "poisson_step": 5,
        "step_runs": [("falling_block", [40, 40, 40], 8), ("porous_bed", [25, 75, 25], 8),
                      ("falling_block", [40, 40, 40], 8, ["projection.preconditioner=sgs"]),
                      ("falling_block", [75, 75, 75], 3), ("porous_bed", [50, 150, 50], 3)],
        "mpi_runs": [("cavity", [64, 64, 64], 8), ("falling_block", [48, 48, 48], 4)], "mpi_rounds": 2,
    },
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--parts", default="poisson,steps,mpi", help="comma list of poisson, steps, mpi (default all)")
    ap.add_argument("--out", help="output directory (default perf/scaling/results or perf/scaling/quick)")
    ap.add_argument("--tables-only", action="store_true", help="rebuild the tables from the CSVs")
    a = ap.parse_args()
    mode = "quick" if a.quick else "full"
    cfg = CONFIGS[mode]
    out = a.out or os.path.join(HERE, "results" if mode == "full" else "quick")
    os.makedirs(out, exist_ok=True)
    tmp = os.path.join(os.environ.get("TMPDIR", "/tmp"), "voigt-scaling-%d" % os.getpid())
    t0 = time.time()
    parts = a.parts.split(",")
    if not a.tables_only:
        for exe in [VOIGT, PSCALE]:
            if not os.path.exists(exe):
                sys.exit("missing %s: build first (scripts/build) or set VOIGT_BUILD_DIR" % exe)
        tpath = os.path.join(out, "timing.json")
        timing = json.load(open(tpath)) if os.path.exists(tpath) else {}
        for name, fn in [("poisson", lambda: part_poisson(cfg, out)), ("steps", lambda: part_steps(cfg, out, tmp)),
                         ("mpi", lambda: part_mpi(cfg, out, tmp))]:
            if name in parts:
                t1 = time.time()
                fn()
                timing[name] = round(time.time() - t1)
                with open(tpath, "w") as f:
                    json.dump(timing, f, indent=1)
    cores = os.cpu_count() or 0
    load = os.getloadavg()[0]
    tpath = os.path.join(out, "timing.json")
    timing = json.load(open(tpath)) if os.path.exists(tpath) else {}
    tt = ", ".join("%s %d s" % kv for kv in timing.items())
    L = ["_Generated by `perf/scaling/run%s` on %s (%d cores, load average %.1f at the end), build %s. "
         "Measured run time per part: %s (total %.1f min)._" % (
             " --quick" if a.quick else "", time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), cores, load,
             os.path.relpath(BUILD, ROOT) if BUILD.startswith(ROOT) else BUILD, tt or "n/a",
             sum(timing.values()) / 60), ""]
    fits = []
    if os.path.exists(os.path.join(out, "poisson.csv")):
        PL, fits = poisson_tables(out)
        L += PL + [""]
    if os.path.exists(os.path.join(out, "step_split.csv")):
        L += step_tables(out) + [""]
    if os.path.exists(os.path.join(out, "mpi.csv")):
        L += mpi_tables(out, cores) + [""]
    ML, _ = model_tables(out, fits)
    L += ML
    with open(os.path.join(out, "tables.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    log("wrote", os.path.relpath(os.path.join(out, "tables.md"), ROOT))
    if mode == "full" and not a.out:
        readme = os.path.join(HERE, "README.md")
        report.replace_section(readme, "<!-- BEGIN RESULTS (perf/scaling/run writes this) -->", "<!-- END RESULTS -->",
                               L, "Scaling")
        log("wrote", os.path.relpath(readme, ROOT))
    shutil.rmtree(tmp, ignore_errors=True)
    log("done in %.0f s" % (time.time() - t0))



if __name__ == "__main__":
    main()
