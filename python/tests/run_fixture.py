"""One small voigt run that the test modules share (made once per process, removed at exit):
a sphere of fluid (radius 0.25) in a fluid of the same density beside a box and a cylinder
obstacle, 12 x 8 x 8 cells of h = 0.125, dt 0.025 to t = 0.2 (8 steps), fields psi and
velocity written at t = 0, 0.1, 0.2, and a line probe `axis` of psi through the sphere's
centre line (x = 0.0625 .. 1.4375 at y = z = 0.5: the x cell centres, on the y and z faces).
VOIGT names the voigt binary (default build/voigt; CTest sets it)."""
import atexit
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), ".."))  # voigt_post
from voigt_post import launch  # noqa: E402

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

_made = None


def made():
    """(temporary folder, the run's output folder inside it)."""
    global _made
    if _made is None:
        tmp = tempfile.mkdtemp(prefix="voigt_post_")
        atexit.register(shutil.rmtree, tmp, True)
        scene = os.path.join(tmp, "carried.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        out = os.path.join(tmp, "run")
        voigt = os.environ.get("VOIGT", os.path.join(launch.REPO, "build", "voigt"))
        subprocess.run(launch.voigt_cmd(voigt, scene, out, overwrite=False), check=True, capture_output=True)
        _made = (tmp, out)
    return _made


class RunFixture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp, cls.out = made()
