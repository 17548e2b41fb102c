#!/usr/bin/python3
"""What an exact projection costs at each tolerance (issue 19): the scene's own projection against
the exact operator (27-point D(1/rho)G, fast diagonalization) at several CG tolerances, run
interleaved (A, B, C, ..., A, B, C, ...), from the scene's start or from a checkpoint of a long run
(the interface is where the projection is hard, and a developed flow has more of it).

    perf/exact_projection/tolerance_sweep SCENE [--set K=V ...] [--restart-from CKPT] --steps N
        [--ranks R] [--tolerances 1e-2,1e-3,1e-4,1e-8] [--precisions single,double]
        [--initial-guesses previous,extrapolate] [--repeats 2] [--out DIR]

Prints one markdown row per variant: CG iterations a step (mean, max), the whole step's wall
seconds (median over repeats, `wall_seconds` of summary.json / steps) and its ratio to the
scene's own projection, and after the projection the max and the mean over cells of |div u| (1/s;
the mean is the measure OpenFOAM's "sum local" continuity error takes times dt; a restart keeps
the checkpointed run's columns, so a run older than that column shows nan), with the max before it. Time ratios are only comparable within one invocation.
"""
import argparse
import os
import re
import shutil
import statistics
import sys
import tempfile

from voigt_post import launch, series


def variants(tols, precisions, guesses):
    out = [("scene", [])]
    for t in tols:
        for p in precisions:
            for g in guesses:
                name = "exact %s" % t + (" %s" % p if len(precisions) > 1 else "") + (
                    " %s" % g if len(guesses) > 1 else "")
                sets = ["projection.operator=exact", "projection.preconditioner=fast_diagonalization",
                        "projection.tolerance=%s" % t, "projection.fd_precision=%s" % p]
                out.append((name, sets + (["projection.initial_guess=%s" % g] if g else [])))
    return out


def measure(out):
    s, c = series.summary(out), series.timeseries(out)
    its, steps = c["poisson_iterations"], len(c["step"])
    return {"its": its, "step_s": s["wall_seconds"] / steps, "steps": steps,
            "div": max(c["max_divergence"]), "mean": max(c.get("mean_divergence", [float("nan")])),
            "before": max(c["max_divergence_predicted"]), "op": s["poisson"]["operator"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--set", action="append", default=[], dest="sets")
    ap.add_argument("--restart-from")
    ap.add_argument("--steps", type=int, required=True, help="steps to run (after the checkpoint's step)")
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--tolerances", default="1e-2,1e-3,1e-4,1e-8")
    ap.add_argument("--precisions", default="single",
                    help="fast diagonalization's precisions, comma-separated: single, double")
    ap.add_argument("--initial-guesses", default="",
                    help="CG initial guesses, comma-separated: previous, extrapolate (default: the scene's)")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--out")
    ap.add_argument("--voigt", default=os.path.join(launch.build_dir(), "voigt"))
    a = ap.parse_args()
    top = a.out or tempfile.mkdtemp(prefix="voigt-tolerance-")
    os.makedirs(top, exist_ok=True)
    # A copy, so that a rebuild of build/ during the sweep cannot swap the binary.
    binary = os.path.join(top, "voigt")
    shutil.copy2(a.voigt, binary)
    first = 0
    if a.restart_from:
        m = re.search(r"checkpoint_(\d+)\.h5$", a.restart_from)
        if not m:
            sys.exit("tolerance_sweep: --restart-from needs a checkpoint_NNNNNNNNN.h5 file")
        first = int(m.group(1))
    vs = variants([t for t in a.tolerances.split(",") if t], [p for p in a.precisions.split(",") if p],
                  [g for g in a.initial_guesses.split(",") if g] or [""])
    res = {name: [] for name, _ in vs}
    for rep in range(a.repeats):
        for name, sets in vs:
            out = os.path.join(top, "%s_r%d" % (name.replace(" ", "_"), rep + 1))
            cmd = launch.voigt_cmd(binary, a.scene, out, ["output.enabled=false"] + a.sets + sets, ranks=a.ranks,
                                   steps=first + a.steps, restart_from=a.restart_from)
            rc, _ = launch.run_logged(cmd, out + ".log", 3600)
            if rc != 0:
                sys.exit("tolerance_sweep: %s failed (exit %d): %s.log" % (name, rc, out))
            res[name].append(measure(out))
            launch.log("%-12s repeat %d: %.3f s a step" % (name, rep + 1, res[name][-1]["step_s"]))
    base = statistics.median(r["step_s"] for r in res["scene"])
    print("%s, %d ranks, %d steps%s, %d repeats; output %s\n" % (
        a.scene, a.ranks, a.steps, " from " + a.restart_from if a.restart_from else "", a.repeats, top))
    print("| projection | CG its a step (mean, max) | s a step | / scene's | max div after (1/s) "
          "| mean div after (1/s) | max div before (1/s) |")
    print("|---|---|---|---|---|---|---|")
    for name, _ in vs:
        r = res[name]
        t = statistics.median(x["step_s"] for x in r)
        its = r[-1]["its"]
        label = "scene's (%s)" % r[-1]["op"] if name == "scene" else name
        print("| %s | %.1f, %d | %.3f | %.2f | %.2e | %.2e | %.2e |" % (
            label, sum(its) / len(its), max(its), t, t / base, r[-1]["div"], r[-1]["mean"], r[-1]["before"]))


if __name__ == "__main__":
    main()
