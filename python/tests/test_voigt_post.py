"""Tests of the analysis package (python/voigt_post) on a real run (run_fixture.py): the
frames of fields.xdmf, the scene record and the picture. test_formulas.py and test_readers.py
test the other modules. Standard library unittest (run by CTest as python.voigt_post; VOIGT
names the voigt binary); the picture test needs Debian's python3-vtk9, python3-h5py and xvfb
(scripts/setup --figures)."""
import os
import shutil
import subprocess
import unittest

import voigt_post
from voigt_post import scene_record, xdmf
from run_fixture import PACKAGE, RunFixture, script


class PackageTest(unittest.TestCase):
    def test_imported_from_this_checkout(self):
        # scripts/setup's voigt.pth (or pip install -e python, or PYTHONPATH) names this checkout's
        # python/; another checkout's package would test that one's code.
        here = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))
        self.assertEqual(os.path.realpath(PACKAGE), here,
                         "voigt_post from %s: rerun scripts/setup here or set PYTHONPATH=%s" % (voigt_post.__file__, here))
        r = script("cases/runs.py", "seconds", "1m", cwd="/")     # a case script from any directory
        self.assertEqual(r.stdout, "60\n")


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
