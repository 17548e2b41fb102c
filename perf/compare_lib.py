"""Helpers of perf/compare: git export, builds, voigt runs, statistics and the report.
Standard library only. perf/compare (compare.py) is the command; perf/README.md describes it.
Launching voigt and the report's number formats come from python/voigt_post (launch, report)."""
import glob
import hashlib
import json
import os
import shutil
import subprocess
import time

from voigt_post import launch
from voigt_post.launch import git, log, run_logged, tail, voigt_cmd  # noqa: F401  (used by compare.py)
from voigt_post.report import failed_runs, fmt, med, spread

ROOT = launch.REPO
NICE = ["nice", "-n", "10"]
# Stages that run inside momentum (once per Runge-Kutta substage): not added to the total.
NESTED = ("stress", "forces")
STAGE_ORDER = ["properties", "advection", "momentum", "stress", "forces", "projection", "corrections",
               "diagnostics"]


def identities(rev):
    """(A, B): dicts describing the revision REV and the working tree."""
    sha = git("rev-parse", "--verify", rev + "^{commit}")
    a = {"rev": rev, "sha": sha, "short": git("rev-parse", "--short", sha),
         "describe": git("describe", "--always", "--tags", sha),
         "subject": git("log", "-1", "--format=%s", sha)}
    changed = [l for l in git("status", "--porcelain", "--untracked-files=normal").splitlines() if l.strip()]
    head = git("rev-parse", "HEAD")
    b = {"rev": "working tree", "sha": head, "short": git("rev-parse", "--short", head),
         "describe": git("describe", "--always", "--tags", "--dirty"),
         "subject": git("log", "-1", "--format=%s", head), "changed_files": changed,
         "diff_stat": git("diff", "--shortstat", "HEAD")}
    return a, b


# ---------------------------------------------------------------- building
def build_env(basedir):
    env = dict(os.environ)
    env["CCACHE_BASEDIR"] = basedir
    return env


def ensure_cmake():
    if shutil.which("cmake") is None:
        log("cmake missing: running scripts/setup")
        subprocess.run([os.path.join(ROOT, "scripts", "setup")], check=True)


def _run_logged(cmd, logf, env, cwd=None):
    with open(logf, "a") as f:
        f.write("$ %s\n" % " ".join(cmd))
        f.flush()
        r = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, env=env, cwd=cwd)
    if r.returncode != 0:
        with open(logf) as f:
            tail = f.read()[-3000:]
        raise SystemExit("build failed (%s), log %s:\n%s" % (" ".join(cmd), logf, tail))


def cmake_build(src, bdir, jobs, basedir, configure):
    """Configures (when asked or when bdir has no cache) and builds the voigt target; returns seconds."""
    t0 = time.time()
    os.makedirs(bdir, exist_ok=True)
    gi = os.path.join(bdir, ".gitignore")  # a build folder inside a work tree stays out of git status
    if not os.path.exists(gi):
        with open(gi, "w") as f:
            f.write("*\n")
    logf = os.path.join(bdir, "compare-build.log")
    open(logf, "w").close()
    env = build_env(basedir)
    if configure or not os.path.exists(os.path.join(bdir, "CMakeCache.txt")):
        _run_logged(NICE + ["cmake", "-S", src, "-B", bdir, "-DCMAKE_BUILD_TYPE=Release"], logf, env)
    _run_logged(NICE + ["cmake", "--build", bdir, "-j%d" % jobs, "--target", "voigt"], logf, env)
    return time.time() - t0


def prepare_a(a, cache, jobs, b_build):
    """Exports revision A into CACHE/<sha>/src (once) and builds its voigt; returns (binary, seconds).
    A's build folder sits inside its export where B's sits inside the work tree (build-compare), and
    CCACHE_BASEDIR is each tree's root: then the compiler lines of A and B are the same relative to
    the build folder and ccache hits across the two trees (system headers keep absolute paths)."""
    top = os.path.join(cache, a["sha"])
    src = os.path.join(top, "src")
    marker = os.path.join(top, "exported")
    if not os.path.exists(marker):
        log("exporting %s into %s" % (a["short"], src))
        shutil.rmtree(src, ignore_errors=True)
        os.makedirs(src)
        arch = subprocess.Popen(["git", "-C", ROOT, "archive", a["sha"]], stdout=subprocess.PIPE)
        tar = subprocess.run(["tar", "-x", "-C", src], stdin=arch.stdout)
        arch.stdout.close()
        if arch.wait() != 0 or tar.returncode != 0:
            raise SystemExit("git archive %s | tar failed" % a["sha"])
        open(marker, "w").close()
    rel = os.path.relpath(b_build, ROOT)
    bdir = os.path.join(src, rel if not rel.startswith("..") else "build-compare")
    binary = os.path.join(bdir, "voigt")
    if os.path.exists(binary) and os.path.getmtime(binary) > os.path.getmtime(marker):
        log("A: %s is built (%s)" % (a["short"], binary))
        return binary, 0.0
    log("A: building %s in %s (log compare-build.log there)" % (a["short"], bdir))
    secs = cmake_build(src, bdir, jobs, src, configure=True)
    log("A: built in %.0f s" % secs)
    return binary, secs


def prepare_b(bdir, jobs, no_build):
    binary = os.path.join(bdir, "voigt")
    if no_build:
        if not os.path.exists(binary):
            raise SystemExit("--no-build: %s does not exist" % binary)
        return binary, 0.0
    log("B: building the working tree in %s" % bdir)
    secs = cmake_build(ROOT, bdir, jobs, ROOT, configure=False)
    log("B: built in %.0f s" % secs)
    return binary, secs


# ---------------------------------------------------------------- running
def metrics(summary, base=None):
    """Per-step figures of one run's summary.json. base: the poisson block of the summary of the
    run that wrote the checkpoint restarted from (its counters carry over into a restart)."""
    n = summary["steps_this_run"]
    wall = summary["wall_seconds"]
    stages = {k: v / n for k, v in summary.get("wall_seconds_per_stage", {}).items()}
    m = {"steps": n, "s_per_step": wall / n, "cell_steps_per_second": summary.get("cell_steps_per_second"),
         "stages": stages}
    top = sum(v for k, v in stages.items() if k not in NESTED)
    m["stages_other"] = wall / n - top
    p = dict(summary.get("poisson") or {})
    if p:
        solves, its = p.get("solves", 0), p.get("iterations_mean", 0) * p.get("solves", 0)
        solve_s, setup_s = p.get("solve_seconds", 0), p.get("setup_seconds", 0)
        if base:
            solves -= base.get("solves", 0)
            its -= base.get("iterations_mean", 0) * base.get("solves", 0)
            solve_s -= base.get("solve_seconds", 0)
            setup_s -= base.get("setup_seconds", 0)
        m["poisson_iterations_mean"] = its / solves if solves > 0 else None
        m["poisson_solve_per_step"] = solve_s / n
        m["poisson_setup_per_step"] = setup_s / n
    if "projection" in stages:
        # The solver set-up (new coefficients: matrix refill, RAP or a new hierarchy) runs in
        # the momentum stage (refreshCoefficients), the solve in the projection stage.
        m["non_poisson"] = wall / n - stages["projection"] - m.get("poisson_setup_per_step", 0)
    return m


def impact_checkpoint(cache, a, a_bin, scene, sets, end_time, timeout):
    """Runs A on the falling block to end_time with a checkpoint at the end (once; cached under
    CACHE/<sha>/fb_impact_<key>, key: the scene file's text and the --set list); returns a dict
    (file, step, t, the poisson block of that run's summary: its counters carry into a restart),
    or (None, why) when A could not write one."""
    with open(scene, "rb") as f:
        text = f.read()
    key = hashlib.sha1(json.dumps([hashlib.sha1(text).hexdigest(), sets, end_time]).encode()).hexdigest()[:10]
    top = os.path.join(cache, a["sha"], "fb_impact_" + key)
    info_f = os.path.join(top, "checkpoint.json")
    if os.path.exists(info_f):
        with open(info_f) as f:
            info = json.load(f)
        if os.path.exists(info["file"]):
            log("impact checkpoint (cached): %s, step %d" % (info["file"], info["step"]))
            return info, None
    os.makedirs(top, exist_ok=True)
    out = os.path.join(top, "run")
    ranks = min(2, os.cpu_count() or 1)  # a checkpoint holds global arrays: any rank count restarts it
    cmd = voigt_cmd(a_bin, scene, out, sets + ["checkpoint.interval=100000000", "checkpoint.keep=1"], ranks=ranks,
                    end_time=end_time)
    logf = os.path.join(top, "run.log")
    log("impact checkpoint: running A to t = %g once (about 6 min at 75^3): %s" % (end_time, " ".join(cmd)))
    rc, secs = run_logged(cmd, logf, timeout)
    files = sorted(glob.glob(os.path.join(out, "checkpoint_*.h5")))
    if rc != 0 or not files or not os.path.exists(os.path.join(out, "summary.json")):
        return None, "A's run to t = %g with a checkpoint failed (exit %s, log %s: %s)" % (
            end_time, rc, logf, tail(logf, 400).strip().replace("\n", " / "))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    info = {"file": files[-1], "step": s["steps"], "t": s["simulated_time"], "poisson": s.get("poisson"),
            "seconds": secs, "ranks": ranks, "command": cmd}
    with open(info_f, "w") as f:
        json.dump(info, f, indent=1)
    log("impact checkpoint: step %d, t = %g, %.0f s" % (info["step"], info["t"], secs))
    return info, None


# ---------------------------------------------------------------- statistics and report
def ratio(a, b):
    return a / b if a and b else None


def verdict(ta, tb):
    """Whole-range comparison: 'B faster' only when every B time is below every A time."""
    if not ta or not tb:
        return "-"
    if len(ta) < 2 or len(tb) < 2:
        return "1 run: no noise measure"
    if max(tb) < min(ta):
        return "B faster"
    if min(tb) > max(ta):
        return "B slower"
    return "within noise"


def aggregate(runs, key):
    """Medians per (scene, ranks) and revision of the successful runs; also the raw times."""
    out = {}
    for rev in ("A", "B"):
        ok = [r["metrics"] for r in runs if r["rev"] == rev and r["ok"] and r["key"] == key]
        stages = sorted({s for m in ok for s in m["stages"]})
        out[rev] = {
            "ok": len(ok), "failed": sum(1 for r in runs if r["rev"] == rev and r["key"] == key and not r["ok"]),
            "times": [m["s_per_step"] for m in ok],
            "s_per_step": med([m["s_per_step"] for m in ok]),
            "cell_steps_per_second": med([m["cell_steps_per_second"] for m in ok]),
            "poisson_iterations_mean": med([m.get("poisson_iterations_mean") for m in ok]),
            "non_poisson": med([m.get("non_poisson") for m in ok]),
            "stages_other": med([m.get("stages_other") for m in ok]),
            "poisson_solve": med([m.get("poisson_solve_per_step") for m in ok]),
            "poisson_setup": med([m.get("poisson_setup_per_step") for m in ok]),
            "stages": {s: med([m["stages"].get(s) for m in ok]) for s in stages},
        }
    return out


def report(meta, keys, agg, runs):
    L = []
    a, b = meta["A"], meta["B"]
    L.append("# perf/compare: %s (A) against the working tree (B)" % a["short"])
    L.append("")
    L.append("- A: `%s` (%s) %s" % (a["sha"], a["describe"], a["subject"]))
    L.append("- B: working tree on `%s`, `git describe --dirty`: %s; %d changed/untracked paths%s" %
             (b["sha"], b["describe"], len(b["changed_files"]),
              (" (" + b["diff_stat"] + ")") if b["diff_stat"] else ""))
    L.append("- date %s, nproc %s, load average at start %s, at end %s" %
             (meta["date"], meta["nproc"], meta["load_start"], meta["load_end"]))
    L.append("- settings: %s; repeats %d (interleaved A, B, A, B); window %s" %
             (meta["settings_text"], meta["repeats"], meta["window_text"]))
    L.append("- binaries: A `%s`, B `%s`; build A %.0f s, B %.0f s; runs %.0f s; total %.0f s" %
             (meta["a_bin"], meta["b_bin"], meta["build_a_s"], meta["build_b_s"], meta["runs_s"],
              meta["total_s"]))
    for note in meta.get("notes", []):
        L.append("- **note**: " + note)
    L.append("")
    L.append("s/step = wall_seconds / steps_this_run of summary.json (first step's one-off work "
             "included), median of the repeats; speed B/A = A time / B time (> 1: B faster); the "
             "min-max range of each is the noise; verdict: 'B faster' / 'B slower' only when the "
             "two ranges do not overlap.")
    L.append("")
    L.append("| scene | ranks | steps | A s/step | A min-max | B s/step | B min-max | speed B/A | verdict "
             "| A cell-steps/s | B cell-steps/s | A Poisson its | B Poisson its | runs ok A, B |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for key in keys:
        scene, ranks, steps = key
        A, B = agg[key]["A"], agg[key]["B"]
        r = ratio(A["s_per_step"], B["s_per_step"])
        L.append("| %s | %d | %d | %s | %s | %s | %s | **%s** | %s | %s | %s | %s | %s | %d/%d, %d/%d |" % (
            scene, ranks, steps, fmt(A["s_per_step"]), spread(A["times"]), fmt(B["s_per_step"]),
            spread(B["times"]), "%.3f" % r if r else "-", verdict(A["times"], B["times"]),
            fmt(A["cell_steps_per_second"], 3), fmt(B["cell_steps_per_second"], 3),
            fmt(A["poisson_iterations_mean"], 3), fmt(B["poisson_iterations_mean"], 3),
            A["ok"], A["ok"] + A["failed"], B["ok"], B["ok"] + B["failed"]))
    L.append("")
    L.append("## Per stage (median seconds per step)")
    L.append("")
    L.append("`stress` and `forces` run inside `momentum` (not added to the total); `other` = total "
             "minus the top-level stages; the Poisson solve runs inside `projection`, its set-up for new "
             "coefficients inside `momentum`; `non-Poisson` = total minus both.")
    for key in keys:
        scene, ranks, steps = key
        A, B = agg[key]["A"], agg[key]["B"]
        L.append("")
        L.append("### %s, %d rank%s, %d steps" % (scene, ranks, "s" if ranks > 1 else "", steps))
        L.append("")
        L.append("| stage | A s/step | B s/step | speed B/A | A share |")
        L.append("|---|---|---|---|---|")
        stages = sorted(set(A["stages"]) | set(B["stages"]),
                        key=lambda s: (STAGE_ORDER.index(s) if s in STAGE_ORDER else 99, s))
        rows = [("**total**", A["s_per_step"], B["s_per_step"])]
        rows += [(s + (" (in momentum)" if s in NESTED else ""), A["stages"].get(s), B["stages"].get(s))
                 for s in stages]
        rows += [("other", A["stages_other"], B["stages_other"]),
                 ("**non-Poisson**", A["non_poisson"], B["non_poisson"]),
                 ("Poisson solve", A["poisson_solve"], B["poisson_solve"]),
                 ("Poisson set-up", A["poisson_setup"], B["poisson_setup"])]
        for name, x, y in rows:
            r = ratio(x, y)
            share = "%.0f %%" % (100 * x / A["s_per_step"]) if x is not None and A["s_per_step"] else "-"
            L.append("| %s | %s | %s | %s | %s |" % (name, fmt(x), fmt(y), "%.3f" % r if r else "-", share))
    failed = [r for r in runs if not r["ok"]]
    if failed:
        L += failed_runs(("%s %s, %d ranks, repeat %d: exit %s; `%s`" % (
            r["rev"], r["scene"], r["ranks"], r["repeat"] + 1, r["rc"], " ".join(r["cmd"])), r["log_tail"]) for r in failed)
    return "\n".join(L) + "\n"
