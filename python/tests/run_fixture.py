"""What the test modules share: small voigt runs, made once per process and removed at exit,
and running a case script on them.

The carried run (made()): a sphere of fluid (radius 0.25) in a fluid of the same density beside
a box and a cylinder obstacle, 12 x 8 x 8 cells of h = 0.125, dt 0.025 to t = 0.2 (8 steps),
fields psi and velocity written at t = 0, 0.1, 0.2, and a line probe `axis` of psi through the
sphere's centre line (x = 0.0625 .. 1.4375 at y = z = 0.5: the x cell centres, on the y and z
faces). case_run(): a case's own scene on a tiny grid for a few steps (the case scripts' tests).
script(): a script of cases/ or perf/ under /usr/bin/python3, with this checkout's voigt_post.
VOIGT names the voigt binary (default build/voigt; CTest sets it)."""
import atexit
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import voigt_post
from voigt_post import launch

REPO = launch.REPO
PACKAGE = os.path.dirname(os.path.dirname(os.path.abspath(voigt_post.__file__)))   # the python/ imported
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
VOIGT = os.environ.get("VOIGT", os.path.join(REPO, "build", "voigt"))

SCENE = """name: carried
domain: {lo: [0, 0, 0], hi: [1.5, 1, 1], cells: [12, 8, 8]}
boundaries: {default: {type: slip}}
time: {end: 0.2, dt: 0.025}
effects: [navier_stokes, level_set, obstacles]
level_set: {phase: ball, shape: {type: sphere, center: [0.4, 0.5, 0.5], radius: 0.25}}
materials: {air: {density: 1, viscosity: 0.01}, ball: {density: 1, viscosity: 0.01}}
fluid: air
obstacles:
  - {type: box, lo: [1.2, 0, 0], hi: [1.5, 0.25, 1]}
  - {type: cylinder, center: [1.35, 0.8, 0.5], radius: 0.1, axis: z}
output: {interval: 0.1, fields: [psi, velocity]}
probes:
  - {name: axis, line: {from: [0.0625, 0.5, 0.5], to: [1.4375, 0.5, 0.5], points: 12}, fields: [psi], interval: 0.1}
"""
H = 0.125
CENTRE, RADIUS = (0.4, 0.5, 0.5), 0.25

_tmp = None
_made = None
_runs = {}


def tmpdir():
    """The process's temporary folder (removed at exit)."""
    global _tmp
    if _tmp is None:
        _tmp = tempfile.mkdtemp(prefix="voigt_post_")
        atexit.register(shutil.rmtree, _tmp, True)
    return _tmp


def made():
    """(temporary folder, the carried run's output folder inside it)."""
    global _made
    if _made is None:
        tmp = tmpdir()
        scene = os.path.join(tmp, "carried.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        out = os.path.join(tmp, "run")
        subprocess.run(launch.voigt_cmd(VOIGT, scene, out, overwrite=False), check=True, capture_output=True)
        _made = (tmp, out)
    return _made


def case_run(name, scene, *sets, end_time=None, steps=None):
    """The output folder of `voigt run SCENE --set SETS` (SCENE relative to cases/ or absolute)
    named NAME in the process's temporary folder, run once per process."""
    if name not in _runs:
        out = os.path.join(tmpdir(), name)
        cmd = launch.voigt_cmd(VOIGT, os.path.join(REPO, "cases", scene), out, sets=sets, steps=steps,
                               end_time=end_time, overwrite=False)
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError("%s: exit %d\n%s" % (" ".join(cmd), r.returncode, r.stderr[-2000:]))
        _runs[name] = out
    return _runs[name]


def script(path, *args, check=True, cwd=None):
    """Runs PATH (relative to the repository) under /usr/bin/python3 with ARGS, on this
    checkout's voigt_post (PYTHONPATH: the python/ the tests imported); returns the completed
    process (text stdout, stderr). With `check`, a non-zero exit fails with its stderr."""
    env = dict(os.environ, PYTHONPATH=PACKAGE + os.pathsep + os.environ.get("PYTHONPATH", ""),
               MPLBACKEND="Agg")
    r = subprocess.run([PYTHON, os.path.join(REPO, path)] + [str(a) for a in args], capture_output=True,
                       text=True, env=env, cwd=cwd)
    if check and r.returncode != 0:
        raise AssertionError("%s %s: exit %d\n%s" % (path, " ".join(map(str, args)), r.returncode, r.stderr[-3000:]))
    return r


def load(path, name=None):
    """A script of cases/ or perf/ (PATH relative to the repository) as a module, without
    running its main: for the tests of its functions."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(name or os.path.splitext(os.path.basename(path))[0],
                                                  os.path.join(REPO, path))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def csv_rows(text):
    """The rows of a CSV text as dicts."""
    import csv
    import io
    return list(csv.DictReader(io.StringIO(text)))


class RunFixture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp, cls.out = made()
