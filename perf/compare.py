#!/usr/bin/python3
"""perf/compare REV: build git revision REV (A) and the working tree (B, uncommitted changes
included) and run both on the same scenes, interleaved A, B, A, B, ...; report the median
seconds per step, cell-steps per second, Poisson iterations and the per-stage split of each,
and the speed ratio B/A (A time / B time: > 1 means B is faster) per scene and rank count.

    perf/compare 70c54aa                          # all scenes, 1 and 2 ranks, 3 repeats
    perf/compare HEAD~3 --quick                   # 1 repeat, half the steps, 1 rank
    perf/compare HEAD --scenes cavity,dam_break --ranks 2 --repeats 5
    perf/compare HEAD --scenes falling_block --fb-window impact   # 20 steps across the impact

A is exported (git archive) into ${VOIGT_COMPARE_CACHE:-~/.cache/voigt-compare}/<sha>/src and
built there once; B is built into ${VOIGT_BUILD_DIR:-<repo>/build-compare}. Only the voigt target
is built. The report goes to stdout and to --out (default perf/results/):
compare-<short sha>.md, and compare-<short sha>.json with every raw run. perf/README.md has more.
"""
import argparse
import datetime
import json
import os
import shutil
import signal
import sys
import tempfile
import time

sys.dont_write_bytecode = True  # no perf/__pycache__ in the work tree
import compare_lib as L  # noqa: E402  (beside this file)

ROOT = L.ROOT
# name: (scene file in the working tree, cells pinned with --set, steps)
SCENES = {
    "falling_block": ("cases/falling_block/falling_block.yaml", [75, 75, 75], 20),
    "porous_bed": ("cases/porous_bed/porous_bed.yaml", [50, 150, 50], 30),
    "dam_break": ("perf/scenes/dam_break.yaml", [64, 64, 64], 20),
    "cavity": ("perf/scaling/cavity.yaml", [64, 64, 64], 20),
}
# The old revision's best projection: the same for both unless --projection default.
BEST_PROJECTION = ["projection.operator=approximate", "projection.preconditioner=multigrid",
                   "projection.multigrid_reuse=RAP", "projection.multigrid_refresh=10"]
IMPACT_T = 0.055  # falling block: the impact window starts here (first impact ~0.06 s)


def parse():
    p = argparse.ArgumentParser(prog="perf/compare", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("rev", help="git revision of A (B is the working tree)")
    p.add_argument("--scenes", default=",".join(SCENES), help="comma list of %s" % ", ".join(SCENES))
    p.add_argument("--ranks", default=None, help="comma list of MPI rank counts (default 1,2; --quick: 1)")
    p.add_argument("--repeats", type=int, default=None, help="runs of each revision (default 3; --quick: 1)")
    p.add_argument("--steps-scale", type=float, default=1.0, help="scale every scene's step count")
    p.add_argument("--quick", action="store_true", help="1 repeat, half the steps, 1 rank")
    p.add_argument("--no-build", action="store_true", help="do not build B (use the existing binary)")
    p.add_argument("--projection", choices=["best", "default"], default="best",
                   help="best (default): --set %s for both; default: each revision's own defaults"
                   % " ".join(BEST_PROJECTION))
    p.add_argument("--set", dest="sets", action="append", default=[], metavar="KEY=VALUE",
                   help="passed to every run (repeatable)")
    p.add_argument("--set-b", dest="sets_b", action="append", default=[], metavar="KEY=VALUE",
                   help="passed to B's runs only, after the others (e.g. a key A does not know, set to "
                   "what A does)")
    p.add_argument("--keep-output", action="store_true",
                   help="do not add --set output.enabled=false (field output is off by default)")
    p.add_argument("--fb-window", choices=["start", "impact"], default="start",
                   help="falling block: the first steps (default) or 20 steps from a checkpoint at t = %g s "
                   "written once by A (impact at ~0.06 s)" % IMPACT_T)
    p.add_argument("--out", default=os.path.join(ROOT, "perf", "results"), help="folder of the report")
    p.add_argument("--cache", default=os.environ.get("VOIGT_COMPARE_CACHE",
                                                     os.path.join(os.path.expanduser("~"), ".cache",
                                                                  "voigt-compare")))
    p.add_argument("--jobs", type=int, default=2, help="build jobs (default 2)")
    p.add_argument("--timeout", type=int, default=1800, help="seconds before one run is killed (default 1800)")
    a = p.parse_args()
    a.scenes = [s.strip() for s in a.scenes.split(",") if s.strip()]
    for s in a.scenes:
        if s not in SCENES:
            p.error("unknown scene %r (known: %s)" % (s, ", ".join(SCENES)))
    a.ranks = [int(r) for r in (a.ranks or ("1" if a.quick else "1,2")).split(",")]
    a.repeats = a.repeats if a.repeats is not None else (1 if a.quick else 3)
    if a.quick:
        a.steps_scale *= 0.5
    return a


def _terminate(signum, frame):
    raise SystemExit("perf/compare: stopped by signal %d" % signum)


def main():
    args = parse()
    signal.signal(signal.SIGTERM, _terminate)  # runs are stopped and the temp folder removed
    t_start = time.time()
    load_start = "%.2f %.2f %.2f" % os.getloadavg()
    A, B = L.identities(args.rev)
    L.log("A = %s (%s), B = working tree (%s, %d changed paths)" %
          (A["short"], A["describe"], B["describe"], len(B["changed_files"])))
    L.ensure_cmake()
    b_build = os.path.abspath(os.environ.get("VOIGT_BUILD_DIR", os.path.join(ROOT, "build-compare")))
    if os.path.realpath(b_build) == os.path.realpath(os.path.join(ROOT, "build")):
        raise SystemExit("VOIGT_BUILD_DIR is build/: perf/compare builds B elsewhere (default build-compare)")
    cache = os.path.abspath(args.cache)
    a_bin, build_a_s = L.prepare_a(A, cache, args.jobs, b_build)
    b_bin, build_b_s = L.prepare_b(b_build, args.jobs, args.no_build)

    common = [] if args.projection == "default" else list(BEST_PROJECTION)
    if not args.keep_output:
        common.append("output.enabled=false")
    notes = []
    window = {s: "first steps" for s in args.scenes}
    restart = {}
    tmp = tempfile.mkdtemp(prefix="voigt-compare-")
    runs, keys = [], []
    t_runs = time.time()
    try:
        plan = []
        for s in args.scenes:
            path, cells, steps = SCENES[s]
            steps = max(1, int(round(steps * args.steps_scale)))
            sets = ["domain.cells=[%s]" % ",".join(map(str, cells))] + common + args.sets
            # Each side runs its own tree's copy of the scene where it has one (a key added
            # since A would make A's loader refuse B's copy); scenes new since A: B's copy.
            scene = os.path.join(ROOT, path)
            a_scene = os.path.join(cache, A["sha"], "src", path)
            scenes_ab = {"A": a_scene if os.path.exists(a_scene) else scene, "B": scene}
            if s == "falling_block" and args.fb_window == "impact":
                info, why = L.impact_checkpoint(cache, A, a_bin, scenes_ab["A"], sets, IMPACT_T, args.timeout * 4)
                if info:
                    probe_out = os.path.join(tmp, "restart_probe")
                    cmd = L.voigt_cmd(b_bin, scene, probe_out, sets + args.sets_b, steps=info["step"] + 1,
                                      restart_from=info["file"])
                    rc, _ = L.run_logged(cmd, os.path.join(tmp, "restart_probe.log"), args.timeout)
                    shutil.rmtree(probe_out, ignore_errors=True)
                    if rc != 0:
                        why = "B refused A's checkpoint %s (exit %s: %s)" % (info["file"], rc, L.tail(
                            os.path.join(tmp, "restart_probe.log"), 400).strip().replace("\n", " / "))
                if why:
                    notes.append("falling_block --fb-window impact: %s; fell back to the first %d steps" % (why, steps))
                    L.log("note: " + notes[-1])
                else:
                    restart[s] = info
                    window[s] = "%d steps from A's checkpoint at step %d, t = %.4g s" % (steps, info["step"],
                                                                                        info["t"])
            for r in args.ranks:
                plan.append((s, scenes_ab, sets, steps, r))
        total = len(plan) * args.repeats * 2
        n = 0
        for s, scenes_ab, sets, steps, ranks in plan:
            key = (s, ranks, steps)
            keys.append(key)
            info = restart.get(s)
            for rep in range(args.repeats):
                for rev, binary in (("A", a_bin), ("B", b_bin)):
                    n += 1
                    out = os.path.join(tmp, "%s_%s_%d_%d" % (rev, s, ranks, rep))
                    nsteps = (info["step"] + steps) if info else steps
                    cmd = L.voigt_cmd(binary, scenes_ab[rev], out, sets + (args.sets_b if rev == "B" else []),
                                      ranks=ranks, steps=nsteps, restart_from=info["file"] if info else None)
                    load = os.getloadavg()[0]
                    rc, secs = L.run_logged(cmd, out + ".log", args.timeout)
                    rec = {"rev": rev, "scene": s, "ranks": ranks, "repeat": rep, "key": key, "cmd": cmd,
                           "rc": rc, "seconds": secs, "load1_start": load, "ok": False}
                    try:
                        with open(os.path.join(out, "summary.json")) as f:
                            rec["summary"] = json.load(f)
                    except (OSError, ValueError):
                        rec["summary"] = None
                    if rc == 0 and rec["summary"] and rec["summary"].get("steps_this_run", 0) > 0:
                        rec["metrics"] = L.metrics(rec["summary"], info["poisson"] if info else None)
                        rec["ok"] = True
                        L.log("[%d/%d] %s %s %d rank(s) #%d: %.4g s/step (%.0f s, load %.1f)" %
                              (n, total, rev, s, ranks, rep + 1, rec["metrics"]["s_per_step"], secs, load))
                    else:
                        rec["log_tail"] = L.tail(out + ".log", 2500)
                        L.log("[%d/%d] %s %s %d rank(s) #%d: FAILED (exit %s), log tail:\n%s" %
                              (n, total, rev, s, ranks, rep + 1, rc, rec["log_tail"][-600:]))
                    runs.append(rec)
                    shutil.rmtree(out, ignore_errors=True)
                    if os.path.exists(out + ".log"):
                        os.remove(out + ".log")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    runs_s = time.time() - t_runs

    agg = {k: L.aggregate(runs, k) for k in keys}
    meta = {"A": A, "B": B, "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S %Z").strip(),
            "nproc": os.cpu_count(), "load_start": load_start, "load_end": "%.2f %.2f %.2f" % os.getloadavg(),
            "repeats": args.repeats, "ranks": args.ranks, "sets_common": common, "sets_extra": args.sets,
            "settings_text": "projection %s%s%s" % (
                args.projection, " (" + " ".join("--set " + s for s in BEST_PROJECTION) + ")"
                if args.projection == "best" else "", (", --set " + ", --set ".join(args.sets)) if args.sets else ""),
            "window_text": "; ".join("%s: %s" % kv for kv in window.items()),
            "a_bin": a_bin, "b_bin": b_bin, "build_a_s": build_a_s, "build_b_s": build_b_s, "runs_s": runs_s,
            "total_s": time.time() - t_start, "notes": notes, "command": sys.argv,
            "restart": restart}
    text = L.report(meta, keys, agg, runs)
    print(text)
    os.makedirs(args.out, exist_ok=True)
    base = os.path.join(args.out, "compare-%s" % A["short"])
    with open(base + ".md", "w") as f:
        f.write(text)
    with open(base + ".json", "w") as f:
        json.dump({"meta": meta, "results": [{"scene": k[0], "ranks": k[1], "steps": k[2], **agg[k]} for k in keys],
                   "runs": [{k: v for k, v in r.items() if k != "key"} for r in runs]}, f, indent=1, default=str)
    L.log("report: %s.md, %s.json" % (base, base))
    return 1 if any(not r["ok"] for r in runs) else 0


if __name__ == "__main__":
    sys.exit(main())
