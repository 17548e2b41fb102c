"""The OpenFOAM side of perf/peers/run.py: install, environment, the interFoam case's set-up,
the timed run and its log (continuity errors, times, iterations)."""
import os
import re
import shutil
import subprocess
import sys
import threading
import time

from voigt_post import launch

HERE = os.path.dirname(os.path.abspath(__file__))
NICE = ["nice", "-n", "10"]
CASE = os.path.join(HERE, "interfoam_dambreak")
FOAM_BASHRC = "/usr/share/openfoam/etc/bashrc"
WATER_CELLS = 16 * 32 * 32  # 0.146 x 0.292 x 0.292 m at h = 0.584/64
DT = 0.002


def die(msg):
    print("perf/peers/run: error: " + msg, file=sys.stderr)
    sys.exit(1)


log = launch.log


def ensure_openfoam(no_install):
    if os.path.exists(FOAM_BASHRC) and shutil.which("interFoam"):
        return
    if no_install:
        die("OpenFOAM is not installed (%s, interFoam); install it: sudo apt-get install -y openfoam" % FOAM_BASHRC)
    log("OpenFOAM missing: apt-get install -y openfoam (Debian package, v1912)")
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    r = subprocess.run(sudo + ["apt-get", "install", "-y", "openfoam"], env=env)
    if r.returncode != 0:
        r = subprocess.run(sudo + ["apt-get", "update"], env=env)
        r = subprocess.run(sudo + ["apt-get", "install", "-y", "openfoam"], env=env)
    if r.returncode != 0 or not os.path.exists(FOAM_BASHRC) or not shutil.which("interFoam"):
        die("could not install OpenFOAM (apt-get install -y openfoam, exit %s)" % r.returncode)


def foam_env():
    """The environment after sourcing OpenFOAM's bashrc (Debian's prints harmless errors about
    foamEtcFile: discarded). interFoam refuses to start without it (no etc/controlDict)."""
    r = subprocess.run(["bash", "-c", ". %s >/dev/null 2>&1; env -0" % FOAM_BASHRC], capture_output=True)
    env = {}
    for item in r.stdout.split(b"\0"):
        if b"=" in item:
            k, v = item.split(b"=", 1)
            env[k.decode()] = v.decode(errors="replace")
    if "WM_PROJECT_DIR" not in env:
        die("sourcing %s did not set WM_PROJECT_DIR" % FOAM_BASHRC)
    return env


def set_entry(path, key, value):
    with open(path) as f:
        s = f.read()
    s2, n = re.subn(r"(?m)^(\s*%s\s+)[^;]*;" % re.escape(key), lambda m: m.group(1) + value + ";", s, count=1)
    if n != 1:
        die("%s: no entry %s" % (path, key))
    with open(path, "w") as f:
        f.write(s2)


def foam_setup(top, ranks, steps, env):
    """Copies the case, sets endTime and the decomposition, runs blockMesh, setFields and
    (ranks > 1) decomposePar. Not timed. Returns the case folder."""
    case = os.path.join(top, "interfoam_np%d" % ranks)
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(CASE, case)
    shutil.copy(os.path.join(case, "0", "alpha.water.orig"), os.path.join(case, "0", "alpha.water"))
    set_entry(os.path.join(case, "system", "controlDict"), "endTime", repr(round(steps * DT, 12)))
    dpd = os.path.join(case, "system", "decomposeParDict")
    set_entry(dpd, "numberOfSubdomains", str(ranks))
    set_entry(dpd, "n", "(1 1 %d)" % ranks)  # as Voigt's decomposition: [1, 1, 2] at 2 ranks
    tools = [["blockMesh"], ["setFields"]] + ([["decomposePar", "-force"]] if ranks > 1 else [])
    for t in tools:
        logf = os.path.join(case, "log." + t[0])
        with open(logf, "w") as f:
            r = subprocess.run(NICE + t, cwd=case, env=env, stdout=f, stderr=subprocess.STDOUT)
        if r.returncode != 0:
            die("%s failed in %s (exit %d):\n%s" % (t[0], case, r.returncode, launch.tail(logf)))
    # The water block must be exactly Voigt's: 16 x 32 x 32 cells of alpha 1.
    with open(os.path.join(case, "0", "alpha.water")) as f:
        txt = f.read()
    m = re.search(r"internalField\s+nonuniform\s+List<scalar>\s*(\d+)\s*\((.*?)\)\s*;", txt, re.S)
    water = sum(1 for v in m.group(2).split() if float(v) == 1.0) if m else None
    if water != WATER_CELLS:
        die("setFields selected %s water cells, expected %d (%s/log.setFields)" % (water, WATER_CELLS, case))
    return case


def run_interfoam(case, ranks, logf, env, timeout):
    """Runs the solver; the time-stepping loop is timed by this script's clock from the log's
    'Starting time loop' line to its 'End' line (the lines are stamped as they arrive)."""
    cmd = ["interFoam"] if ranks == 1 else launch.MPIRUN + [str(ranks), "interFoam", "-parallel"]
    t0 = time.monotonic()
    t_loop = t_end = None
    killed = []
    with open(logf, "w") as f:
        p = subprocess.Popen(cmd, cwd=case, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             start_new_session=True, text=True, errors="replace", bufsize=1)
        timer = threading.Timer(timeout, lambda: (killed.append(1), launch.stop(p)))
        timer.start()
        try:
            for line in p.stdout:
                now = time.monotonic()
                f.write(line)
                s = line.strip()
                if s == "Starting time loop" and t_loop is None:
                    t_loop = now
                elif s == "End":
                    t_end = now
            rc = p.wait()
        except BaseException:
            launch.stop(p)
            raise
        finally:
            timer.cancel()
    wall = time.monotonic() - t0
    if killed:
        rc = "timeout after %d s" % timeout
    return cmd, rc, wall, (t_end - t_loop) if (t_loop is not None and t_end is not None) else None


def parse_foam_log(logf):
    with open(logf, errors="replace") as f:
        text = f.read()
    blocks = re.split(r"(?m)^Time = ", text)[1:]  # one per time step
    cont = re.compile(r"time step continuity errors : sum local = (\S+), global = (\S+), cumulative = (\S+)")
    final, every, cumulative = [], [], None
    for b in blocks:
        c = cont.findall(b)
        if c:
            final.append(float(c[-1][0]))
            every += [float(x[0]) for x in c]
            cumulative = float(c[-1][2])
    ex = re.findall(r"ExecutionTime = (\S+) s\s+ClockTime = (\S+) s", text)
    vf = [float(x) for x in re.findall(r"Phase-1 volume fraction = (\S+)", text)]
    its = [int(x) for x in re.findall(r"Solving for p_rgh.*No Iterations (\d+)", text)]
    return {
        "steps": len([b for b in blocks if "ExecutionTime" in b]),
        "continuity_final_last": final[-1] if final else None,
        "continuity_final_max": max(final) if final else None,
        "continuity_any_corrector_max": max(every) if every else None,
        "continuity_cumulative_last": cumulative,
        "execution_time_s": float(ex[-1][0]) if ex else None,
        "clock_time_s": float(ex[-1][1]) if ex else None,
        "alpha_volume_fraction_first": vf[0] if vf else None,
        "alpha_volume_fraction_last": vf[-1] if vf else None,
        "p_rgh_iterations_per_step": (sum(its) / len(blocks)) if blocks and its else None,
    }
