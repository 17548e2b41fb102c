"""Launching voigt (Python standard library only): the command line of a run, under mpirun
when it has more than one rank, and running it with a time limit in its own process group.

    from voigt_post import launch
    cmd = launch.voigt_cmd(launch.REPO + "/build/voigt", "cases/zalesak/zalesak.yaml", "/tmp/z",
                           sets=["domain.cells=[64,64,2]"], ranks=2, steps=10)
    rc, seconds = launch.run_logged(cmd, "/tmp/z.log", timeout=600)
"""
import os
import signal
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# As root (containers) and with more ranks than cores (2-core machines); ranks yield the core
# while they wait (no busy polling): on a shared, loaded machine a spinning rank steals the
# core its partner needs (measured: 2 ranks 2.2x faster with it than without).
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "--mca", "mpi_yield_when_idle", "1", "-np"]


def build_dir():
    """$VOIGT_BUILD_DIR, else <repo>/build (as scripts/build)."""
    return os.environ.get("VOIGT_BUILD_DIR", os.path.join(REPO, "build"))


def voigt_cmd(binary, scene, out, sets=(), ranks=1, steps=None, end_time=None, restart_from=None,
              overwrite=True):
    """`voigt run SCENE -o OUT [--overwrite] [--steps N] [--end-time T] [--restart-from F]
    [--set KEY=VALUE ...]`, behind mpirun -np RANKS when RANKS > 1."""
    cmd = [binary, "run", scene, "-o", out]
    if overwrite:
        cmd.append("--overwrite")
    if steps is not None:
        cmd += ["--steps", str(steps)]
    if end_time is not None:
        cmd += ["--end-time", repr(end_time)]
    if restart_from:
        cmd += ["--restart-from", restart_from]
    for s in sets:
        cmd += ["--set", s]
    return (MPIRUN + [str(ranks)] + cmd) if ranks > 1 else cmd


def stop(p):
    """SIGTERM to the process group of p (mpirun and its ranks), SIGKILL after 15 s."""
    try:
        os.killpg(p.pid, signal.SIGTERM)
        p.wait(timeout=15)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    except ProcessLookupError:
        pass


def run_logged(cmd, logf, timeout):
    """Runs cmd in its own process group, output to LOGF; returns (exit code, seconds); on
    timeout kills that group and the code is the text "timeout after N s"."""
    t0 = time.time()
    with open(logf, "w") as f:
        p = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT, start_new_session=True)
        try:
            rc = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            stop(p)
            rc = "timeout after %d s" % timeout
        except BaseException:  # Ctrl-C: the run is in its own session, so stop it here
            stop(p)
            raise
    return rc, time.time() - t0


def tail(path, n=1500):
    """The last N characters of a log file ("" when there is none)."""
    try:
        with open(path, errors="replace") as f:
            return f.read()[-n:]
    except OSError:
        return ""


def git(*args, check=True):
    """`git -C <repo> ARGS`, its output stripped; a failure ends the program when `check`."""
    r = subprocess.run(["git", "-C", REPO] + list(args), capture_output=True, text=True)
    if check and r.returncode != 0:
        raise SystemExit("git %s: %s" % (" ".join(args), r.stderr.strip()))
    return r.stdout.strip()


def log(*a):
    """A line on stderr behind the time of day."""
    print(time.strftime("%H:%M:%S"), *a, file=sys.stderr, flush=True)
