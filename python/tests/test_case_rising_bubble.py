"""cases/rising_bubble's scripts on tiny runs of its scenes: case1.yaml on 16 x 32 x 2 cells to
t = 0.1 (fields every 0.05) for bubble.py (finished, show, row, table, figures; figures.py through
it) and static_drop.yaml on 16 x 16 x 2 to t = 0.02 for laplace.py. Each run about a second."""
import csv
import json
import os
import shutil
import tempfile
import unittest

from run_fixture import case_run, script

try:
    import h5py  # noqa: F401  (scripts/setup --figures: numpy, h5py, matplotlib)
    import matplotlib  # noqa: F401
except ImportError:
    h5py = None


@unittest.skipIf(h5py is None, "h5py, matplotlib (scripts/setup --figures)")
class RisingBubble(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = case_run("rb_case1", "rising_bubble/case1.yaml", "domain.cells=[16,32,2]", "output.interval=0.05",
                           end_time=0.1)
        cls.drop = case_run("rb_drop", "rising_bubble/static_drop.yaml", "domain.cells=[16,16,2]",
                            "output.interval=0.01", end_time=0.02)
        cls.tmp = tempfile.mkdtemp(prefix="rb_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, True)

    def test_show_finished(self):
        text = script("cases/rising_bubble/bubble.py", "show", self.out).stdout.splitlines()
        self.assertTrue(text[0].startswith("case 1 ("))
        got = {line.split()[0]: line.split() for line in text[1:]}
        self.assertEqual(set(got), {"min_circularity", "t_min_circularity", "max_rise_velocity", "t_max_rise_velocity",
                                    "centroid_y_t3"})
        self.assertAlmostEqual(float(got["min_circularity"][1]), 1.0, delta=0.1)   # a circle (the box from the record)
        self.assertIn("TP2D", got["min_circularity"])
        self.assertEqual(script("cases/rising_bubble/bubble.py", "finished", self.out, check=False).returncode, 0)

    def test_row_table_figures(self):
        res, dig = os.path.join(self.tmp, "results.csv"), os.path.join(self.tmp, "digests")
        script("cases/rising_bubble/bubble.py", "row", self.out, "--csv", res, "--digests", dig)
        with open(res) as f:
            row = next(csv.DictReader(f))
        with open(os.path.join(self.out, "summary.json")) as f:
            steps = json.load(f)["steps"]
        self.assertEqual((row["case"], row["n"], row["h"], row["steps"]), ("1", "16", "1/16", str(steps)))
        with open(os.path.join(dig, "case1_16.json")) as f:
            d = json.load(f)
        xs, ys = d["shape"]
        self.assertAlmostEqual(max(xs) - min(xs), 0.5, delta=0.07)     # the bubble's diameter, in the box's x
        self.assertAlmostEqual((max(ys) + min(ys)) / 2, 0.5, delta=0.05)
        table = script("cases/rising_bubble/bubble.py", "table", "--csv", res).stdout
        self.assertIn("| Voigt h = 1/16 |", table)
        self.assertIn("| TP2D |", table)
        script("cases/rising_bubble/bubble.py", "figures", "--csv", res, "--digests", dig, "-o", self.tmp)
        for png in ("case1.png", "convergence.png"):
            self.assertTrue(os.path.getsize(os.path.join(self.tmp, png)) > 1000, png)

    def test_laplace(self):
        text = script("cases/rising_bubble/laplace.py", self.drop, "--check", "0.9").stdout
        self.assertRegex(text, r"^jump -?[\d.]+, Laplace 4\.00000 \(R = 0\.25000, the scene's\), error [-+][\d.]+ %\n$")
        r = script("cases/rising_bubble/laplace.py", self.drop, "--check", "1e-9", check=False)
        self.assertEqual((r.returncode, r.stdout.splitlines()[-1]), (1, "FAIL: outside 1e-09"))


if __name__ == "__main__":
    unittest.main()
