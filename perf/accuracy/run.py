#!/usr/bin/python3
"""Accuracy against time: sweep one knob at a time around a base setting on
reference cases with known answers; record error, wall time, steps and
cell-steps per second; write results.csv, one Pareto plot per case and the
markdown table in README.md (between the RESULTS markers).

    perf/accuracy/run                 # full study (budget: about 20 min on 2 busy cores)
    perf/accuracy/run --quick         # smaller grids, fewer points (about 4 min)
    perf/accuracy/run --big           # also the 256^2 grids (+30 min or more)
    perf/accuracy/run --presets       # only the presets (and base points), merged into results.csv
    perf/accuracy/run --cases taylor_green --voigt /tmp/build/voigt
                                      # one case: the other cases' rows of results.csv are kept

Wall time is the run's own `wall_seconds` (summary.json: the time loop, without
process start-up); every point with a wall time under --repeat-below seconds is
run 3 times in all (interleaved with the others) and the minimum kept; the base
point of each case runs at the start and the end of the case's points in every round.

Cases (each: a scene in cases/, a base setting, knobs, an error measure):
  taylor_green  RMS velocity error over the nodes at t = 1 against the exact decaying
                solution (as tests/flow/test_taylor_green.cpp), read from the last HDF5
                output (python/voigt_post/fields.py: h5py, or h5dump).
  zalesak       after one rotation: shape error E = sum |H(psi0) - H(psi)| dA / L with
                the sharp Heaviside at cell centres and psi0 the initial (exact) psi,
                L = 143.80 the exact perimeter (as tests/levelset/test_transport.cpp);
                also the sharp-area change from summary.json.
  elastic_couette  from rest, COUETTE_PERIODS periods: RMS over the nodes (line probe) and the
                last period's 8 samples of u_x - u_exact, / V, against the exact periodic
                sharp-interface state of python/voigt_post/couette.py; also the
                max and the previous period's RMS (how settled the run is).
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

from voigt_post import launch, series
from accuracy_errors import COUETTE_PERIODS, COUETTE_SAMPLES, COUETTE_T, couette_error, tg_error, zalesak_error
from accuracy_tables import plot, readme

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = launch.REPO


# ---------------------------------------------------------------- cases and knobs
def tg_res(n):
    # cubic cells: 4 cells along the uniform z direction
    return ["domain.cells=[%d,%d,4]" % (n, n), "domain.hi=[6.283185307179586,6.283185307179586,%.17g]"
            % (4 * 2 * math.pi / n)]


def zal_res(n):
    return ["domain.cells=[%d,%d,2]" % (n, n), "domain.hi=[100,100,%.17g]" % (2 * 100.0 / n)]


def couette_res(n):
    # n cells across the 10 mm gap; x and z two cubic cells each; the line probe on the nodes
    h = 0.01 / n
    return ["domain.cells=[2,%d,2]" % n, "domain.hi=[%.17g,0.01,%.17g]" % (2 * h, 2 * h),
            "probes=[{name: profile, line: {from: [%.17g, 0, %.17g], to: [%.17g, 0.01, %.17g], points: %d}, "
            "fields: [velocity], interval: %.17g}]" % (h, h, h, h, n + 1, COUETTE_T / COUETTE_SAMPLES)]


PCS = ["sgs", "jacobi", "none", "multigrid"]
LIMITERS = ["minmod", "van_leer", "mc", "none"]

# Each knob: name -> (values, function value -> list of --set). The base value of each
# knob is in "base"; a knob's base point is the case's base run (run once, shared).
CASES = {
    "taylor_green": {
        "scene": "cases/taylor_green/taylor_green.yaml",
        "error": tg_error,
        "error_label": "RMS velocity error at t = 1",
        "common": ["output.interval=0", "output.fields=[velocity]", "projection.max_iterations=5000", "probes=[]"],
        "base": {"resolution": 32, "cfl": 0.5, "limiter": "minmod", "operator": "approximate",
                 "tolerance": 1e-8, "preconditioner": "sgs", "pc_exact": None},
        "knobs": {
            "resolution": ([16, 32, 64, 128], tg_res),
            "cfl": ([0.1, 0.25, 0.5, 0.8, 0.95], lambda v: ["time.cfl=%g" % v]),
            "limiter": (LIMITERS, lambda v: ["advection.limiter=" + v]),
            "operator": (["approximate", "exact"], lambda v: ["projection.operator=" + v]),
            "tolerance": ([1e-3, 1e-4, 1e-6, 1e-8, 1e-10], lambda v: ["projection.tolerance=%g" % v]),
            "preconditioner": (PCS, lambda v: ["projection.preconditioner=" + v]),
            # the preconditioners again on the exact (27-point) operator, where SGS may not pay
            "pc_exact": (PCS, lambda v: ["projection.operator=exact", "projection.preconditioner=" + v]),
        },
        "quick": {"resolution": [16, 32, 64], "cfl": [0.25, 0.5, 0.8], "tolerance": [1e-4, 1e-6, 1e-8],
                  "pc_exact": ["sgs", "none"]},
        "big": {"resolution": [16, 32, 64, 128, 256]},
        "preset_fine": 64,
    },
    "zalesak": {
        "scene": "cases/zalesak/zalesak.yaml",
        "error": zalesak_error,
        "error_label": "shape error E after one rotation (length units; h = 100/n)",
        "common": ["output.interval=0", "output.fields=[psi]"],
        "base": {"resolution": 64, "cfl": 0.5, "limiter": "minmod", "reinit_interval": 1,
                 "reinit_iterations": 2},
        "knobs": {
            "resolution": ([64, 128], zal_res),  # 256: --big (about 12 min on its own)
            "cfl": ([0.25, 0.5, 0.8, 0.95], lambda v: ["time.cfl=%g" % v]),
            "limiter": (LIMITERS, lambda v: ["advection.limiter=" + v]),
            "reinit_interval": ([1, 2, 4, 8, "off"],
                                lambda v: ["effects=[prescribed_flow, level_set]"] if v == "off"
                                else ["reinit.interval=%d" % v]),
            "reinit_iterations": ([1, 2, 4], lambda v: ["reinit.iterations=%d" % v]),
        },
        "quick": {"resolution": [64], "cfl": [0.5, 0.8], "limiter": ["minmod", "mc"],
                  "reinit_interval": [1, 4], "reinit_iterations": [2]},
        "big": {"resolution": [64, 128, 256]},
        "preset_fine": 128,
    },
    # Elastic Couette (cases/elastic_couette): the scene (50 cells across, 8 periods from rest)
    # at 24 cells and COUETTE_PERIODS periods; x and z keep two cubic cells (hi = 2 h), the
    # probe sits on the nodes. dt is the explicit viscous limit (viscous_safety), not the CFL
    # number: the velocities are 1e-4 m/s. Poisson: the right-hand side holds only O(V^2)
    # normal stresses. The error floor is the kappa = 2 h smoothed interface (first order in h).
    "elastic_couette": {
        "scene": "cases/elastic_couette/elastic_couette.yaml",
        "error": couette_error,
        "error_label": "RMS u error / V over the last of %d periods from rest (nodes)" % COUETTE_PERIODS,
        "common": ["time.end=%.17g" % (COUETTE_PERIODS * COUETTE_T), "output.interval=0",
                   "output.fields=[velocity]"],
        "base": {"resolution": 24, "viscous_safety": 0.9, "cfl": 0.5, "limiter": "minmod",
                 "operator": "exact", "tolerance": 1e-6, "preconditioner": "sgs", "smoothing": 2,
                 "rotation": "cayley"},
        "knobs": {
            "resolution": ([12, 24, 48], couette_res),
            "viscous_safety": ([0.5, 0.9], lambda v: ["time.viscous_safety=%g" % v]),
            "cfl": ([0.25, 0.5, 0.9], lambda v: ["time.cfl=%g" % v]),
            "limiter": (["minmod", "mc"], lambda v: ["advection.limiter=" + v]),
            "operator": (["approximate", "exact"], lambda v: ["projection.operator=" + v]),
            "tolerance": ([1e-4, 1e-6, 1e-10], lambda v: ["projection.tolerance=%g" % v]),
            "preconditioner": (["sgs", "jacobi", "none"], lambda v: ["projection.preconditioner=" + v]),
            # kappa in cells (Eq. 4): the interface smoothing that sets the error floor
            "smoothing": ([1, 1.5, 2, 3], lambda v: ["level_set.smoothing=%g" % v]),
            "rotation": (["cayley", "explicit"], lambda v: ["elasticity.rotation=" + v]),
        },
        "quick": {"resolution": [12, 24], "viscous_safety": [], "cfl": [], "limiter": [],
                  "operator": ["approximate"], "tolerance": [1e-4], "preconditioner": [], "smoothing": [1, 3],
                  "rotation": []},
        "quick_base": {"resolution": 12},
    },
}

PRESETS = ["fast", "balanced", "accurate"]
# The keys a preset sets (src/scene/presets.cpp). A preset never overrides a key the scene
# writes, so the preset runs use a copy of the case's scene without them.
PRESET_KEYS = [("time", "cfl"), ("advection", "limiter"), ("projection", "operator"),
               ("projection", "tolerance"), ("projection", "preconditioner"), ("reinit", "interval"),
               ("reinit", "iterations"), ("level_set", "smoothing")]


def scene_without_preset_keys(scene, work):
    try:
        import yaml
    except ImportError:
        sys.exit("the preset runs need PyYAML (apt-get install python3-yaml)")
    with open(os.path.join(ROOT, scene)) as f:
        doc = yaml.safe_load(f)
    for sec, key in PRESET_KEYS:
        if isinstance(doc.get(sec), dict):
            doc[sec].pop(key, None)
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "preset_" + os.path.basename(scene))
    with open(out, "w") as f:
        yaml.safe_dump(doc, f, sort_keys=False)
    return out


# ---------------------------------------------------------------- running
def run_once(voigt, scene, sets, out):
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = launch.voigt_cmd(voigt, os.path.join(ROOT, scene), out, sets, overwrite=False)
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    proc = time.time() - t0
    if p.returncode != 0:
        return None, proc, (p.stderr.strip().splitlines() or ["exit %d" % p.returncode])[-1]
    return series.summary(out), proc, ""


def build_points(args):
    """(case, knob, value, sets) for every point; the base of each case once, as knob 'base'."""
    pts = []
    for cname, c in CASES.items():
        if args.cases and cname not in args.cases:
            continue
        base = dict(c["base"])
        if args.quick:
            base.update(c.get("quick_base", {}))

        def sets_for(over):
            b = dict(base)
            b.update(over)
            s = list(c["common"])
            for k, v in b.items():
                if v is not None:  # None: a knob that only exists as a variation (pc_exact)
                    s += c["knobs"][k][1](v)
            return s

        first = len(pts)
        pts.append((cname, "base", "", sets_for({}), c["scene"]))
        presets = []
        if args.presets_only or not args.no_presets:
            stripped = scene_without_preset_keys(c["scene"], args.work)
            for p in PRESETS:
                s = list(c["common"]) + c["knobs"]["resolution"][1](base["resolution"]) + ["preset=" + p]
                presets.append((cname, "preset", p, s, stripped))
            fine = c.get("preset_fine")  # the presets once more on a finer grid, with the base there
            if fine and not args.quick:
                tag = "n=%d" % fine
                presets.append((cname, "base", tag, sets_for({"resolution": fine}), c["scene"]))
                for p in PRESETS:
                    s = list(c["common"]) + c["knobs"]["resolution"][1](fine) + ["preset=" + p]
                    presets.append((cname, "preset", p + " " + tag, s, stripped))
        if args.presets_only:
            pts += presets
            pts.append(pts[first])
            continue
        for knob, (values, _) in c["knobs"].items():
            if args.knobs and knob not in args.knobs:
                continue
            if args.quick:
                values = c.get("quick", {}).get(knob, values)
            if args.big:
                values = c.get("big", {}).get(knob, values)
            for v in values:
                if v == base[knob]:
                    continue  # the base point
                pts.append((cname, knob, v, sets_for({knob: v}), c["scene"]))
        pts += presets
        # The base once more at the end of the case: a repeat of it (minimum kept), so that a
        # burst of load at one moment does not set the reference every other point is read against.
        pts.append(pts[first])
    return pts


FIELDS = ["case", "knob", "value", "error", "error_max", "error_prev", "error_cells", "area_change", "h_area_change",
          "wall_seconds", "wall_runs", "process_seconds", "steps", "cells", "cell_steps_per_second",
          "poisson_its_mean", "max_divergence", "dt_reasons", "status", "sets"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--voigt", default=os.path.join(ROOT, "build", "voigt"))
    ap.add_argument("--quick", action="store_true", help="smaller grids, fewer points (~4 min)")
    ap.add_argument("--big", action="store_true", help="add the finest grids (TG 256^2, Zalesak 256^2: +30 min)")
    ap.add_argument("--cases", nargs="*", help="subset of: " + ", ".join(CASES))
    ap.add_argument("--knobs", nargs="*", help="subset of knobs")
    ap.add_argument("--presets", dest="presets_only", action="store_true",
                    help="run only the base points and the presets; merge into results.csv")
    ap.add_argument("--merge", metavar="TAG",
                    help="keep results.csv rows this run does not measure; this run's base is saved as base_TAG")
    ap.add_argument("--no-presets", action="store_true", help="leave the presets out of the study")
    ap.add_argument("--repeat-below", type=float, default=10.0,
                    help="points faster than this (s) run 3 times, minimum kept (default 10)")
    ap.add_argument("--work", default=os.path.join(tempfile.gettempdir(), "voigt-accuracy"))
    ap.add_argument("--out", default=HERE, help="where results.csv, the plots and README.md are")
    ap.add_argument("--no-readme", action="store_true")
    ap.add_argument("--plot-only", action="store_true", help="redraw the plots from results.csv, run nothing")
    args = ap.parse_args()
    if args.plot_only:
        with open(os.path.join(args.out, "results.csv")) as f:
            plot(CASES, list(csv.DictReader(f)), args.out)
        return
    if not os.access(args.voigt, os.X_OK):
        sys.exit("no voigt binary at %s (build first, or --voigt PATH)" % args.voigt)
    pts = build_points(args)
    t_start = time.time()
    results = {}
    case_time = {}  # seconds spent on each case's runs (all rounds, error measures included)
    print("%d points; work dir %s" % (len(pts), args.work), flush=True)
    for rnd in range(3):
        for i, (cname, knob, v, sets, scene) in enumerate(pts):
            key = (cname, knob, str(v))
            r = results.get(key)
            if (rnd > 0 or r is not None) and (r is None or r["status"] != "ok" or
                                               r["wall_seconds"] >= args.repeat_below):
                continue
            out = os.path.join(args.work, "%s_%s_%s" % (cname, knob, str(v).replace("/", "_")))
            t_point = time.time()
            summary, proc, err = run_once(args.voigt, scene, sets, out)
            case_time[cname] = case_time.get(cname, 0.0) + time.time() - t_point
            if summary is None:
                results[key] = {"case": cname, "knob": knob, "value": v, "status": "failed: " + err,
                                "sets": " ".join(sets), "process_seconds": proc, "wall_runs": 1}
                print("  %-12s %-18s %-10s FAILED %s" % (cname, knob, v, err), flush=True)
                continue
            wall = summary["wall_seconds"]
            if r is not None:  # a repeat: keep the minimum
                r["wall_runs"] += 1
                if wall < r["wall_seconds"]:
                    r.update(wall_seconds=wall, process_seconds=proc,
                             cell_steps_per_second=summary["cell_steps_per_second"])
                print("  %-12s %-18s %-10s repeat %d: %.2f s (min %.2f)" % (cname, knob, v, rnd + 1, wall,
                                                                           r["wall_seconds"]), flush=True)
                continue
            t_point = time.time()
            m = CASES[cname]["error"](out, summary)
            case_time[cname] += time.time() - t_point
            g = summary["grid"]["cells"]
            r = {"case": cname, "knob": knob, "value": v, "status": "ok", "sets": " ".join(sets),
                 "wall_seconds": wall, "wall_runs": 1, "process_seconds": proc, "steps": summary["steps"],
                 "cells": g[0] * g[1] * g[2], "cell_steps_per_second": summary["cell_steps_per_second"],
                 "poisson_its_mean": summary.get("poisson", {}).get("iterations_mean", ""),
                 "max_divergence": summary.get("last_step", {}).get("max_divergence", ""),
                 "dt_reasons": ";".join("%s:%d" % kv for kv in summary.get("dt_reasons", {}).items())}
            r.update(m)
            results[key] = r
            print("  %-12s %-18s %-10s error %.4g  wall %.2f s  steps %d  (%.0f s elapsed)"
                  % (cname, knob, v, m["error"], wall, summary["steps"], time.time() - t_start), flush=True)
            shutil.rmtree(out, ignore_errors=True)
    elapsed = time.time() - t_start
    print("study wall time: %.0f s" % elapsed)

    rows = list(results.values())
    ran = sorted({p[0] for p in pts}, key=list(CASES).index)
    csv_path = os.path.join(args.out, "results.csv")
    merge = "presets" if args.presets_only else args.merge
    if os.path.exists(csv_path):
        with open(csv_path) as f:
            old = list(csv.DictReader(f))
        if merge:  # keep the earlier rows this run did not measure
            for r in rows:
                if r["knob"] == "base":
                    r["knob"] = "base_" + merge  # the base again, timed in the same run as these points
            new = {(r["case"], r["knob"], str(r["value"])) for r in rows}
            old = [r for r in old if (r["case"], r["knob"], r["value"]) not in new]
        else:  # the cases this run measured are replaced; the rows of the other cases are kept
            old = [r for r in old if r["case"] not in ran]
        order = {c: i for i, c in enumerate(CASES)}
        rows = sorted(old + rows, key=lambda r: order.get(r["case"], len(order)))  # stable: old rows first
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow(r)
    print("wrote", csv_path)
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    plot(CASES, rows, args.out, ran)
    if not args.no_readme:
        readme(CASES, rows, args, elapsed, ran, case_time)


if __name__ == "__main__":
    main()
