#!/usr/bin/python3
"""perf/peers/run: Voigt against OpenFOAM's interFoam on the same 3-D dam break (issue 19).

For each rank count: sets up the interFoam case (perf/peers/interfoam_dambreak: blockMesh,
setFields, decomposePar; not timed), then runs interFoam and Voigt (two variants: the scene as
written, and Voigt's default projection) interleaved, A, B, C, A, B, C, ...; reports median
cell-steps/s of each, the ratio Voigt/interFoam, the min-max across repeats, and each code's
continuity error. Report in --out (peers.md, peers.json) and on stdout. perf/peers/README.md
describes what is measured and what differs between the two codes.

    perf/peers/run                      # ranks 1 and 2, 2 repeats, 50 steps
    perf/peers/run --ranks 2 --repeats 1 --steps 5 --variants scene   # a quick check
    perf/peers/run --variants scene,exact-1e-3,exact-1e-4             # the exact operator at a tolerance
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import tempfile
import time

from voigt_post import launch, series
from voigt_post.report import failed_runs, fmt, med, spread
from peers_foam import DT, NICE, die, ensure_openfoam, foam_env, foam_setup, parse_foam_log, run_interfoam

ROOT = launch.REPO
SCENE = os.path.join(ROOT, "perf", "scenes", "dam_break.yaml")
CELLS = 64 ** 3
VARIANTS = {
    # name: (description, how the scene is obtained)
    "scene": "perf/scenes/dam_break.yaml as written: approximate (7-point) operator, multigrid, tolerance 1e-6",
    "defaults": "the same scene without its projection section: Voigt's defaults, exact (27-point) "
                "operator without its matrix, fast diagonalization, tolerance 1e-3 (the exact operator's "
                "default with two densities), extrapolated initial guess",
}
EXACT = "exact-"  # exact-TOL: the scene with the exact operator at tolerance TOL, e.g. exact-1e-3


def describe(v):
    if v.startswith(EXACT):
        return ("the scene with the exact (27-point) operator, fast diagonalization, tolerance %s "
                "(Belos: relative to the right-hand side's norm)" % v[len(EXACT):])
    return VARIANTS[v]


def variant_sets(v):
    if v.startswith(EXACT):
        return ["projection.operator=exact", "projection.preconditioner=fast_diagonalization",
                "projection.tolerance=" + v[len(EXACT):]]
    return []


log = launch.log


# ---------------------------------------------------------------- Voigt
def ensure_voigt(path, top):
    if not os.path.exists(path):
        log("%s missing: building it (nice -n 10 scripts/build)" % path)
        env = dict(os.environ)
        bdir = os.path.dirname(os.path.abspath(path))
        if bdir != os.path.join(ROOT, "build"):
            env["VOIGT_BUILD_DIR"] = bdir
        r = subprocess.run(NICE + [os.path.join(ROOT, "scripts", "build")], env=env)
        if r.returncode != 0 or not os.path.exists(path):
            die("building voigt failed (exit %d)" % r.returncode)
    # A copy, so that a rebuild of build/ during the measurement cannot swap the binary.
    snap = os.path.join(top, "voigt")
    shutil.copy2(path, snap)
    return snap


def defaults_scene(top):
    """The scene without its top-level projection section (Voigt's default projection)."""
    with open(SCENE) as f:
        lines = f.read().splitlines(True)
    out, skip = [], False
    for ln in lines:
        if re.match(r"^[A-Za-z_]", ln):
            skip = ln.startswith("projection:")
        if not skip:
            out.append(ln)
    p = os.path.join(top, "dam_break_defaults.yaml")
    with open(p, "w") as f:
        f.write("# perf/peers/run: perf/scenes/dam_break.yaml without its projection section\n")
        f.writelines(out)
    return p


def run_voigt(binary, scene, ranks, steps, out, logf, timeout, sets=()):
    cmd = launch.voigt_cmd(binary, scene, out, ["output.enabled=false"] + list(sets), ranks=ranks, steps=steps)
    rc, wall = launch.run_logged(cmd, logf, timeout)
    return cmd, rc, wall


def parse_voigt(out):
    s = series.summary(out)
    cols = series.timeseries(out)
    div, dts, its = cols.get("max_divergence", []), cols.get("dt", []), cols.get("poisson_iterations", [])
    pred, drift = cols.get("max_divergence_predicted", []), cols.get("volume_drift", [])
    mean = cols.get("mean_divergence", [])
    return {
        "steps": s.get("steps_this_run"),
        "loop_s": s.get("wall_seconds"),
        "decomposition": (s.get("grid") or {}).get("decomposition"),
        "max_divergence_max": max(div) if div else None,
        "max_divergence_last": div[-1] if div else None,
        "max_divergence_dt_max": max(d * t for d, t in zip(div, dts)) if div else None,
        "max_divergence_dt_last": div[-1] * dts[-1] if div else None,
        "max_divergence_predicted_max": max(pred) if pred else None,
        "mean_divergence_dt_max": max(d * t for d, t in zip(mean, dts)) if mean else None,
        "mean_divergence_dt_last": mean[-1] * dts[-1] if mean else None,
        "volume_drift_last": drift[-1] if drift else None,
        "poisson_iterations_mean": (sum(its) / len(its)) if its else None,
        "poisson_operator": (s.get("poisson") or {}).get("operator"),
    }


# ---------------------------------------------------------------- report
def e(x):
    return "-" if x is None else "%.2e" % x


def uptime():
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "load %.2f %.2f %.2f" % os.getloadavg()


def make_report(meta, runs, ranks_list, codes):
    L = ["# perf/peers: Voigt against interFoam, 3-D dam break 64^3", ""]
    L.append("- date %s, nproc %s; `uptime` at start: `%s`; at end: `%s`" %
             (meta["date"], meta["nproc"], meta["uptime_start"], meta["uptime_end"]))
    L.append("- Voigt: `%s` (copy of `%s`, built %s), HEAD `%s` (`%s`)" %
             (meta["voigt"], meta["voigt_source"], meta["voigt_mtime"], meta["head"], meta["describe"]))
    L.append("- interFoam: OpenFOAM %s (Debian package `openfoam` %s), case `perf/peers/interfoam_dambreak`" %
             (meta["foam_version"], meta["foam_deb"]))
    L.append("- %d steps of fixed dt %g s, %d cells; repeats %d, interleaved %s per rank count; "
             "2 ranks: `%s`" % (meta["steps"], DT, CELLS, meta["repeats"], ", ".join(codes),
                                " ".join(launch.MPIRUN + ["2"])))
    L.append("- seconds = the time-stepping loop: interFoam from its log's `Starting time loop` line to its "
             "`End` line (stamped by this script as they arrive; mesh and field reading excluded); Voigt "
             "`wall_seconds` of `summary.json` (its step loop; scene set-up excluded). cell-steps/s = "
             "%d x steps / seconds. Process wall clock (start to exit, set-up included) and interFoam's own "
             "ExecutionTime (CPU s of rank 0) and ClockTime are in the second table." % CELLS)
    L.append("- total %.0f s" % meta["total_s"])
    L.append("")
    L.append("| code | ranks | cell-steps/s (median) | min-max | loop s (median) | ratio Voigt/interFoam "
             "| runs ok |")
    L.append("|---|---|---|---|---|---|---|")
    agg = {}
    for ranks in ranks_list:
        for c in codes:
            ok = [r for r in runs if r["code"] == c and r["ranks"] == ranks and r["ok"]]
            n = [r for r in runs if r["code"] == c and r["ranks"] == ranks]
            rates = [CELLS * r["steps"] / r["loop_s"] for r in ok if r["loop_s"]]
            walls = [CELLS * r["steps"] / r["wall_s"] for r in ok]
            agg[(c, ranks)] = {"rate": med(rates), "rates": rates, "loop_s": med([r["loop_s"] for r in ok]),
                               "wall_rate": med(walls), "ok": len(ok), "n": len(n)}
        base = agg[("interFoam", ranks)]
        for c in codes:
            a = agg[(c, ranks)]
            r = a["rate"] / base["rate"] if a["rate"] and base["rate"] else None
            a["ratio"] = r
            a["wall_ratio"] = a["wall_rate"] / base["wall_rate"] if a["wall_rate"] and base["wall_rate"] else None
            L.append("| %s | %d | %s | %s | %s | %s | %d/%d |" % (
                c, ranks, fmt(a["rate"], 3), spread(a["rates"], lambda x: fmt(x, 3)), fmt(a["loop_s"]),
                "-" if c == "interFoam" else ("**%.3f**" % r if r else "-"), a["ok"], a["n"]))
    L.append("")
    L.append("Process wall clock (set-up, reading and MPI start included) and interFoam's own clocks, medians:")
    L.append("")
    L.append("| code | ranks | process wall s | cell-steps/s on it | ratio Voigt/interFoam on it "
             "| interFoam ExecutionTime s | ClockTime s |")
    L.append("|---|---|---|---|---|---|---|")
    for ranks in ranks_list:
        for c in codes:
            ok = [r for r in runs if r["code"] == c and r["ranks"] == ranks and r["ok"]]
            a = agg[(c, ranks)]
            L.append("| %s | %d | %s | %s | %s | %s | %s |" % (
                c, ranks, fmt(med([r["wall_s"] for r in ok])), fmt(a["wall_rate"], 3),
                "-" if c == "interFoam" else ("%.3f" % a["wall_ratio"] if a["wall_ratio"] else "-"),
                fmt(med([r["m"].get("execution_time_s") for r in ok])) if c == "interFoam" else "-",
                fmt(med([r["m"].get("clock_time_s") for r in ok])) if c == "interFoam" else "-"))
    L.append("")
    L.append("## Continuity (last repeat of each)")
    L.append("")
    L.append("interFoam: `time step continuity errors : sum local` = dt x the volume-weighted mean over cells "
             "of |div phi| (dimensionless), after the last PISO corrector of each step (last step, max over "
             "steps), and the max over every corrector (the first correctors of a step are larger); "
             "phase-1 volume fraction at the first and last step (mass of water, 6 digits as printed). "
             "Voigt: `max_divergence` of `timeseries.csv` (1/s: the max over cells of |div u| after the "
             "projection, last step and max over steps); in the x dt columns `mean_divergence` (the mean "
             "over cells of |div u|, the measure of interFoam's sum local) times dt, and under other the "
             "max times dt; `volume_drift` (relative water volume change) at the last step.")
    L.append("")
    L.append("| code | ranks | error last | error max | x dt last | x dt max | other | mass |")
    L.append("|---|---|---|---|---|---|---|---|")
    for ranks in ranks_list:
        for c in codes:
            ok = [r for r in runs if r["code"] == c and r["ranks"] == ranks and r["ok"]]
            if not ok:
                L.append("| %s | %d | - | - | - | - | failed | - |" % (c, ranks))
                continue
            m = ok[-1]["m"]
            if c == "interFoam":
                v0, v1 = m["alpha_volume_fraction_first"], m["alpha_volume_fraction_last"]
                mass = "volume fraction %s -> %s" % (v0, v1)
                L.append("| %s | %d | - | - | %s (sum local) | %s (sum local) | any corrector max %s; "
                         "cumulative %s; p_rgh PCG its/step %s | %s |" % (
                             c, ranks, e(m["continuity_final_last"]), e(m["continuity_final_max"]),
                             e(m["continuity_any_corrector_max"]), e(m["continuity_cumulative_last"]),
                             fmt(m["p_rgh_iterations_per_step"], 3), mass))
            else:
                L.append("| %s | %d | %s 1/s | %s 1/s | %s (mean) | %s (mean) | max x dt last %s, max %s; "
                         "before projection max %s 1/s; "
                         "%s operator, Poisson its/step %s; decomposition %s | volume_drift %s |" % (
                             c, ranks, e(m["max_divergence_last"]), e(m["max_divergence_max"]),
                             e(m.get("mean_divergence_dt_last")), e(m.get("mean_divergence_dt_max")),
                             e(m["max_divergence_dt_last"]), e(m["max_divergence_dt_max"]),
                             e(m["max_divergence_predicted_max"]), m["poisson_operator"],
                             fmt(m["poisson_iterations_mean"], 3), m["decomposition"],
                             e(m["volume_drift_last"])))
    L.append("")
    L.append("Voigt variants: " + "; ".join("`%s`: %s" % (v, describe(v)) for v in meta["variants"]) + ".")
    failed = [r for r in runs if not r["ok"]]
    if failed:
        L += failed_runs(("%s, %d ranks, repeat %d: exit %s; `%s`; log `%s`" % (
            r["code"], r["ranks"], r["repeat"] + 1, r["rc"], " ".join(r["cmd"]), r["log"]), launch.tail(r["log"]))
            for r in failed)
    return "\n".join(L) + "\n", agg


# ---------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ranks", default="1,2", help="rank counts, comma-separated (default 1,2)")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--steps", type=int, default=50)
    ap.add_argument("--out", help="output folder (default: a new folder under the system temp dir)")
    ap.add_argument("--voigt", default=os.path.join(ROOT, "build", "voigt"),
                    help="voigt binary (default build/voigt; built with scripts/build when missing)")
    ap.add_argument("--variants", default="scene,defaults",
                    help="Voigt variants, comma-separated, of: %s, %sTOL (e.g. exact-1e-3)" % (
                        ", ".join(VARIANTS), EXACT))
    ap.add_argument("--timeout", type=int, default=1800, help="seconds per run")
    ap.add_argument("--no-install", action="store_true", help="fail instead of installing openfoam")
    a = ap.parse_args()
    try:
        ranks_list = [int(x) for x in a.ranks.split(",") if x.strip()]
    except ValueError:
        die("--ranks: comma-separated integers")
    variants = [v for v in a.variants.split(",") if v]
    for v in variants:
        if v not in VARIANTS and not (v.startswith(EXACT) and re.fullmatch(r"[0-9.]+(e-?[0-9]+)?", v[len(EXACT):])):
            die("--variants: unknown %r (known: %s, %sTOL)" % (v, ", ".join(VARIANTS), EXACT))
    if a.steps < 1 or a.repeats < 1 or not ranks_list or min(ranks_list) < 1:
        die("--steps, --repeats and --ranks must be positive")
    top = os.path.abspath(a.out) if a.out else tempfile.mkdtemp(prefix="voigt-peers-")
    os.makedirs(top, exist_ok=True)
    t_start = time.time()
    ensure_openfoam(a.no_install)
    env = foam_env()
    voigt = ensure_voigt(os.path.abspath(a.voigt), top)
    scenes = {v: SCENE for v in variants}
    if "defaults" in variants:
        scenes["defaults"] = defaults_scene(top)
    deb = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "openfoam"], capture_output=True, text=True)
    meta = {"date": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "nproc": os.cpu_count(), "uptime_start": uptime(),
            "voigt": voigt, "voigt_source": os.path.abspath(a.voigt),
            "voigt_mtime": time.strftime("%Y-%m-%d %H:%M", time.localtime(os.path.getmtime(a.voigt))),
            "head": launch.git("rev-parse", "--short", "HEAD"), "describe": launch.git("describe", "--always", "--dirty"),
            "foam_version": env.get("WM_PROJECT_VERSION"), "foam_deb": deb.stdout.strip() or "?",
            "steps": a.steps, "repeats": a.repeats, "variants": variants, "ranks": ranks_list}
    log("output in %s; %s" % (top, meta["uptime_start"]))
    codes = ["interFoam"] + ["voigt-" + v for v in variants]
    runs = []
    for ranks in ranks_list:
        log("interFoam set-up for %d rank%s (blockMesh, setFields%s; not timed)" %
            (ranks, "s" if ranks > 1 else "", ", decomposePar" if ranks > 1 else ""))
        case = foam_setup(top, ranks, a.steps, env)
        for rep in range(a.repeats):
            for c in codes:
                tag = "%s_np%d_r%d" % (c, ranks, rep + 1)
                logf = os.path.join(top, tag + ".log")
                r = {"code": c, "ranks": ranks, "repeat": rep, "log": logf}
                if c == "interFoam":
                    cmd, rc, wall, loop = run_interfoam(case, ranks, logf, env, a.timeout)
                    r.update(cmd=cmd, rc=rc, wall_s=wall, loop_s=loop)
                    m = parse_foam_log(logf) if os.path.exists(logf) else {}
                else:
                    out = os.path.join(top, tag)
                    v = c[len("voigt-"):]
                    cmd, rc, wall = run_voigt(voigt, scenes[v], ranks, a.steps, out, logf, a.timeout,
                                              variant_sets(v))
                    r.update(cmd=cmd, rc=rc, wall_s=wall)
                    try:
                        m = parse_voigt(out)
                    except (OSError, ValueError, KeyError) as ex:
                        m = {"error": str(ex)}
                    r["loop_s"] = m.get("loop_s")
                r["m"] = m
                r["steps"] = m.get("steps")
                r["ok"] = rc == 0 and r["loop_s"] is not None and r["steps"] == a.steps
                runs.append(r)
                log("%-16s %d rank%s, repeat %d: %s; loop %s s, process %.1f s%s" % (
                    c, ranks, "s" if ranks > 1 else " ", rep + 1, "ok" if r["ok"] else "FAILED (exit %s)" % rc,
                    fmt(r["loop_s"]), wall,
                    ", %.3g cell-steps/s" % (CELLS * a.steps / r["loop_s"]) if r["ok"] else ""))
    meta["uptime_end"] = uptime()
    meta["total_s"] = time.time() - t_start
    text, agg = make_report(meta, runs, ranks_list, codes)
    with open(os.path.join(top, "peers.md"), "w") as f:
        f.write(text)
    with open(os.path.join(top, "peers.json"), "w") as f:
        json.dump({"meta": meta, "runs": runs,
                   "summary": [dict(code=c, ranks=k, **{x: y for x, y in v.items()})
                               for (c, k), v in agg.items()]}, f, indent=1, default=str)
    print(text)
    print("report: %s/peers.md, %s/peers.json" % (top, top))
    if any(not r["ok"] for r in runs):
        die("%d run(s) failed (see the report)" % sum(1 for r in runs if not r["ok"]))


if __name__ == "__main__":
    main()
