"""cases/rayleigh_taylor: tips.py on a tiny run of its scene (8 x 64 x 2 cells to t = 0.3, psi
and density every 0.1; under a second), also as a run without a scene record (the case's file
stands in); linear_theory.py's functions only (its full run takes minutes of dense eigenproblems)."""
import math
import os
import shutil
import tempfile
import unittest

from run_fixture import case_run, load, script

try:
    import numpy as np
    import scipy  # noqa: F401
except ImportError:  # scripts/setup --figures (numpy); scipy for linear_theory.py
    np = None


@unittest.skipIf(np is None, "numpy, scipy (scripts/setup --figures)")
class RayleighTaylor(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = case_run("rt", "rayleigh_taylor/rayleigh_taylor.yaml", "domain.cells=[8,64,2]",
                           "domain.ranks=[1,1,1]", end_time=0.3)
        cls.tmp = tempfile.mkdtemp(prefix="rt_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, True)

    def tips(self, run, *extra):
        r = script("cases/rayleigh_taylor/tips.py", run, *extra)
        rows = np.loadtxt(os.path.join(run, "tips.csv"), delimiter=",", skiprows=1)
        with open(os.path.join(run, "tips.csv")) as f:
            self.assertEqual(f.readline().strip(), "t_star,t_T,bubble,spike")
        return r, rows

    def test_tips(self):
        run = os.path.join(self.tmp, "run")
        shutil.copytree(self.out, run)
        png, snaps = os.path.join(self.tmp, "tips.png"), os.path.join(self.tmp, "snaps.png")
        r, rows = self.tips(run, "--png", png, "--snapshots", snaps)
        self.assertIn("h = 1/16", r.stdout)                           # 4 H over 64 cells, in units of H
        self.assertEqual(list(np.round(rows[:, 0], 6)), [0, 0.1, 0.2, 0.3])
        np.testing.assert_allclose(rows[:, 1], rows[:, 0] / math.sqrt(2), atol=1e-6)   # t_T = t sqrt(A g / H)
        self.assertAlmostEqual(rows[0, 2], 0.1, delta=0.01)           # y = 2 + 0.1 cos(2 pi x): bubble at x = 0
        self.assertAlmostEqual(rows[0, 3], -0.1, delta=0.01)          # and spike at x = 1/2
        self.assertTrue(os.path.exists(png) and os.path.exists(snaps))
        # A run from before scene records: the case's rayleigh_taylor.yaml, the same numbers.
        old = os.path.join(self.tmp, "old")
        shutil.copytree(self.out, old)
        os.remove(os.path.join(old, "scene.yaml"))
        r2, rows2 = self.tips(old)
        self.assertIn("no scene record", r2.stderr)
        np.testing.assert_array_equal(rows2, rows)

    def test_linear_theory_functions(self):
        lt = load("cases/rayleigh_taylor/linear_theory.py", "rt_linear_theory")
        re, A = lt.scene_defaults()
        self.assertEqual((re, A), (256.0, 0.5))                       # the scene's Re and Atwood number
        k, nu = 2 * math.pi, 1 / re
        exact = lt.sharp_equal_nu(A, 1.0, k, nu)
        approx = math.sqrt(A * k + nu ** 2 * k ** 4) - nu * k * k
        self.assertLess(exact, approx)                                 # the vortical layer slows it (README: 9 %)
        self.assertLess(approx, math.sqrt(A * k))                      # viscosity slows the inviscid rate
        smooth = lt.diffuse(A, 1.0, k, nu, 0.25, N=200)                # a wide band grows slower still
        self.assertTrue(0 < smooth < exact, smooth)


if __name__ == "__main__":
    unittest.main()
