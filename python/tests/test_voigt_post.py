"""Tests of the analysis package (python/voigt_post) on a real run: a sphere of fluid in a
fluid of the same density beside a box and a cylinder obstacle, 12 x 8 x 8 cells, outputs at
t = 0, 0.1, 0.2.
Standard library unittest (run by CTest as python.voigt_post; VOIGT names the voigt binary);
the picture test needs Debian's python3-vtk9, python3-h5py and xvfb (scripts/setup --figures)."""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from voigt_post import scene_record, xdmf  # noqa: E402

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
output: {interval: 0.1, fields: [psi]}
"""


class RunFixture(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="voigt_post_")
        scene = os.path.join(cls.tmp, "carried.yaml")
        with open(scene, "w") as f:
            f.write(SCENE)
        cls.out = os.path.join(cls.tmp, "run")
        voigt = os.environ.get("VOIGT", "build/voigt")
        subprocess.run([voigt, "run", scene, "-o", cls.out], check=True, capture_output=True)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)


class XdmfTest(RunFixture):
    def test_frames_in_time_order_with_geometry(self):
        fr = xdmf.frames(self.out)
        self.assertEqual([round(f.t, 9) for f in fr], [0.0, 0.1, 0.2])   # every output.interval
        for f in fr:
            self.assertEqual(list(f.cells), [12, 8, 8])                    # x y z, not XDMF's z y x
            self.assertEqual(list(f.origin), [0.0, 0.0, 0.0])
            for s, h in zip(f.spacing, (0.125, 0.125, 0.125)):
                self.assertAlmostEqual(s, h, places=12)
            self.assertTrue(os.path.exists(f.path), f.path)

    def test_upto_and_errors(self):
        self.assertEqual(len(xdmf.frames(self.out, upto=0.1)), 2)
        with self.assertRaises(ValueError):
            xdmf.frames(self.out, upto=-1)
        with self.assertRaises(OSError):
            xdmf.frames(os.path.join(self.tmp, "nowhere"))


class SceneRecordTest(RunFixture):
    def test_record_and_cylinder(self):
        sc = scene_record.scene(self.out)
        self.assertEqual(sc["name"], "carried")
        self.assertEqual(scene_record.cylinder(self.out), (1.35, 0.8, 0.1))
        self.assertIsNone(scene_record.scene(self.tmp))                    # no record there
        seg = os.path.join(self.out, "scene_segment2.yaml")                # a restart's changed scene
        with open(seg, "w") as f:
            f.write("name: segment\n")
        try:
            self.assertEqual(scene_record.record_path(self.out), seg)
            self.assertEqual(scene_record.scene(self.out)["name"], "segment")
        finally:
            os.remove(seg)


@unittest.skipUnless(shutil.which("xvfb-run") or os.environ.get("DISPLAY"), "needs xvfb (scripts/setup --figures)")
class PictureTest(RunFixture):
    def test_png_of_two_times(self):
        png = os.path.join(self.tmp, "p.png")
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "picture")
        r = subprocess.run([script, self.out, "-o", png, "--times", "0", "0.2", "--panel", "200", "150"],
                           capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        with open(png, "rb") as f:
            head = f.read(24)
        self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n")
        w, h = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
        self.assertEqual((w, h), (2 * 200, 150 + 28))   # 2 panels; no colour bar without a stress field
        self.assertIn("wrote", r.stdout)


if __name__ == "__main__":
    unittest.main()
