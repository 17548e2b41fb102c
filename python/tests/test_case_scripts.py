"""The case scripts of cases/ball_pool, cavity_disk, sphere_collision, elastic_couette and
cases/thumbnails.py on tiny runs of their scenes (each about a second):
- ball_pool/plots.py: 8 x 12 x 8 cells to t = 0.25 (six outputs);
- cavity_disk/paths.py: 16 x 16 x 2 to its end, t = 8;
- sphere_collision/collision.py: a made-up run folder (a collision needs ~1e4 steps on a grid
  that resolves the spheres): its timeseries.csv of two bodies closing at 0.4 m/s and parting
  at 0.3 m/s, and the case's scene as its record, so every number it prints is known;
- elastic_couette/couette.py: --check, --smoothing, the analytic plot, and --probe on
  2 x 10 x 2 cells to t = 0.05 s;
- thumbnails.py: all three cases, as it runs them (about 6 s), figures into a temporary folder."""
import os
import shutil
import tempfile
import unittest

from run_fixture import REPO, VOIGT, case_run, load, script

try:
    import numpy as np
    import h5py  # noqa: F401
    import matplotlib  # noqa: F401
except ImportError:  # scripts/setup --figures
    np = None


@unittest.skipIf(np is None, "numpy, h5py, matplotlib (scripts/setup --figures)")
class CaseScripts(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="cases_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, True)

    def test_ball_pool_plots(self):
        run = case_run("ball_pool", "ball_pool/ball_pool.yaml", "domain.cells=[8,12,8]", end_time=0.25)
        png = os.path.join(self.tmp, "pool.png")
        script("cases/ball_pool/plots.py", run, "--no-hide", run, "-o", png)
        self.assertTrue(os.path.getsize(png) > 1000)
        record = os.path.join(run, "scene.yaml")
        os.rename(record, record + ".away")     # the tank comes from the record: without one, a message
        try:
            r = script("cases/ball_pool/plots.py", run, "-o", png, check=False)
            self.assertIn("no scene record", r.stderr)
        finally:
            os.rename(record + ".away", record)

    def test_cavity_disk_paths(self):
        run = case_run("cavity_disk", "cavity_disk/cavity_disk.yaml", "domain.cells=[16,16,2]")
        png = os.path.join(self.tmp, "paths.png")
        text = script("cases/cavity_disk/paths.py", run, run, "-o", png).stdout.splitlines()
        self.assertEqual(len(text), 2)
        self.assertRegex(text[0], r"^%s: largest x after t = 4: 0\.\d{4} at t = [4-7]\.\d\d; at t = 8\.00: "
                                  r"\(0\.\d{4}, 0\.\d{4}\)$" % run)
        self.assertTrue(os.path.exists(png))

    def collision_run(self):
        d = os.path.join(self.tmp, "collision")
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "timeseries.csv"), "w") as f:
            f.write("step,t,solid_left_vx,solid_right_vx,solid_gap_left_right,solid_right_cx,solid_left_cx,"
                    "volume_drift_left,volume_drift_right\n")
            for k in range(161):
                t = k * 0.0005   # centroids 15 mm apart, closing at 0.4 m/s to 10.2 mm at t = 12 ms, then parting at 0.3
                dist = 0.015 - 0.4 * t if t < 0.012 else 0.0102 + 0.3 * (t - 0.012)
                v = 0.2 if t < 0.012 else -0.15
                f.write("%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n" % (
                    k, t, v, -v, dist - 0.01, 0.03 + dist / 2, 0.03 - dist / 2, 1e-4 * t, -2e-4 * t))
        shutil.copy(os.path.join(REPO, "cases", "sphere_collision", "sphere_collision.yaml"),
                    os.path.join(d, "scene.yaml"))   # R = 5 mm, 72 cells over 6 cm
        return d

    def test_sphere_collision(self):
        d = self.collision_run()
        png = os.path.join(self.tmp, "collision.png")
        text = script("cases/sphere_collision/collision.py", d, "--png", png).stdout.splitlines()
        self.assertEqual(text[2], "| 6 | 0.4000 | 0.3000 | 0.750 | 0.200 | 0.24 | 0.0120 | 1.6e-05 |")
        self.assertTrue(os.path.exists(png))
        r = load("cases/sphere_collision/collision.py", "collision").analyse(d)
        self.assertAlmostEqual(r["e"], 0.75, places=9)

    def test_elastic_couette(self):
        cou = "cases/elastic_couette/couette.py"
        self.assertEqual(script(cou, "--check").stdout.splitlines()[-1], "check: ok")
        text = script(cou, "--smoothing", "24").stdout
        self.assertTrue(text.startswith("24 cells: smoothed vs sharp periodic state, RMS (nodes, period) / V = 5.475e-03"))
        png = os.path.join(self.tmp, "analytic.png")
        self.assertEqual(script(cou, "-o", png).stdout, "wrote %s\n" % png)
        run = case_run("elastic_couette", "elastic_couette/elastic_couette.yaml", "domain.cells=[2,10,2]",
                       "domain.ranks=[1,1,1]", end_time=0.05)
        png = os.path.join(self.tmp, "probe.png")
        lines = script(cou, "--probe", os.path.join(run, "probe_profile.csv"), "-o", png).stdout.splitlines()
        samples = [x.split() for x in lines[1:-1]]
        self.assertEqual(len(samples), 7)                       # every T/8 to t = 0.05 s, and the end
        self.assertEqual(samples[0], ["0.000", "2.861e-01"])  # from rest: the periodic state's RMS at t = 0
        self.assertEqual(lines[-1], "wrote %s" % png)

    def test_thumbnails(self):
        figs = os.path.join(self.tmp, "thumbnails")
        text = script("cases/thumbnails.py", "-o", os.path.join(self.tmp, "runs"), "--voigt", VOIGT,
                      "--figures", figs).stdout
        self.assertIn("all done in", text)
        self.assertEqual(sorted(os.listdir(figs)), ["channel_thumbnail.png", "shear_wave_thumbnail.png",
                                                    "taylor_green_thumbnail.png"])
        th = load("cases/thumbnails.py", "thumbnails")
        y = np.linspace(0, 1, 11)
        np.testing.assert_allclose(th.couette_exact(y, 50.0, 0.1), y, atol=1e-12)                  # steady: linear
        np.testing.assert_allclose(th.poiseuille_exact(y, 500.0, 0.8, 0.1), 4 * y * (1 - y), atol=1e-6)


if __name__ == "__main__":
    unittest.main()
