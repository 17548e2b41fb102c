"""The cases' table.py (falling block, porous bed): the paper-vs-Voigt tables quote results.csv
and, for runs not finished, the ledger; with --readme they replace only what lies between their
markers; the porous bed's fit of the gradient against mu_S is least squares, its Ergun value
takes the gas, inflow and diameter from the case's scene and packing; grid_cost.py (both cases)
on results.csv rows."""
import csv
import os
import tempfile
import unittest

from voigt_post import ergun, scene_record
from run_fixture import REPO, load, script

CASES = os.path.join(REPO, "cases")
RESULT = {"run_id": "mu1000_extend+global+exact_75", "steps": "3667", "wall_s": "5100", "ranks": "2",
          "slowing_s": "0.0607", "slowing_vy": "-0.535", "impact_gap_h": "0.52", "first_impact_s": "0.0597",
          "rebound_mm": "8.2", "rebound_to_s": "0.1267", "second_contact_s": "0.1465", "base_within_2h_s": "0.3288",
          "first_bending_peak_mm": "3.75", "first_bending_peak_s": "0.0803", "max_energy_ratio": "0.990"}
LEDGER = {"run_id": "mu2000_extend+global+exact_75", "state": "wall_limit", "t_reached": "0.21", "steps": "1500",
          "wall_s": "1200.5", "to_finish_s": "2000"}


def write(path, *rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


class TableTest(unittest.TestCase):
    def test_quotes_the_csvs_and_keeps_the_readme(self):
        with tempfile.TemporaryDirectory() as tmp:
            res, led, readme = (os.path.join(tmp, n) for n in ("results.csv", "runs.csv", "README.md"))
            write(res, RESULT)
            write(led, LEDGER)
            with open(readme, "w") as f:
                f.write("# before\n<!-- table.py: begin -->\nold table\n<!-- table.py: end -->\nafter\n")
            script("cases/falling_block/table.py", "--results", res, "--ledger", led, "--readme", readme)
            with open(readme) as f:
                doc = f.read()
            self.assertTrue(doc.startswith("# before\n<!-- table.py: begin -->\n"))
            self.assertTrue(doc.endswith("<!-- table.py: end -->\nafter\n"))
            self.assertNotIn("old table", doc)
            for v in RESULT.values():
                if v != RESULT["run_id"]:
                    self.assertIn(v, doc)
            self.assertIn("*not finished*: wall_limit at t = 0.21 s (1500 steps, 1200.5 s); to finish ~2000 s", doc)
            self.assertEqual(doc.count("*not run*"), 4)      # 5000 extend and the three integrate runs
            rows = [line for line in doc.splitlines() if line.startswith("| ")]
            self.assertEqual(len(rows), 1 + 8)               # header and the eight quantities
            self.assertTrue(all(r.count(" | ") == 7 for r in rows))   # quantity, paper and six runs


class NotRunTest(unittest.TestCase):
    def test_quotes_the_approximate_twin(self):
        from voigt_post import ledger as runs
        res = {"mu1000_integrate+global_75": {"steps": "7444", "wall_s": "11084", "ranks": "1", "t_end": "0.5000"},
               "mu2000_integrate+global_75": {"steps": "900", "wall_s": "80", "ranks": "1", "t_end": "0.0800"}}
        self.assertEqual(runs.not_run(res, "mu1000_integrate+global+exact_75", 0.5),
                         "*not run*; on the approximate projection 7444 steps, 11084 s on 1 rank(s)")
        self.assertEqual(runs.not_run(res, "mu2000_integrate+global+exact_75", 0.5), "*not run*")  # twin short of 0.5 s
        self.assertEqual(runs.not_run(res, "mu5000_integrate+global+exact_75", 0.5), "*not run*")  # no twin
        self.assertEqual(runs.not_run(res, "mu1000_integrate+global_75", 0.5), "*not run*")  # no twin of its own


class PorousTableTest(unittest.TestCase):
    def test_fit_and_cells(self):
        table = load("cases/porous_bed/table.py", "porous_table")
        slope, icpt, r2 = table.fit([100, 250, 1000], [60.0, 75.0, 150.0])   # on the line 0.1 mu + 50
        self.assertAlmostEqual(slope, 0.1, places=12)
        self.assertAlmostEqual(icpt, 50.0, places=10)
        self.assertAlmostEqual(r2, 1.0, places=12)
        self.assertIsNone(table.fit([100, 250], [1.0, 2.0]))   # two points: no fit worth the name
        # Ergun at e = 0.4 (Eq. 23 by hand: 0.6 / 0.064 * 0.01 / 0.025 * (150 * 0.6 * 1e-5 / 2.5e-3 + 1.75) = 7.91 Pa/m)
        flow = ergun.bed_flow(scene_record.load(os.path.join(CASES, "porous_bed", "porous_bed.yaml")),
                              os.path.join(CASES, "porous_bed", "packing.json"))
        self.assertEqual(flow, {"rho": 1.0, "mu": 1e-5, "u": 0.1, "d": 0.025, "g": 9.81})   # the paper's
        self.assertAlmostEqual(ergun.gradient(0.4, **flow), 0.6 / 0.064 * 0.4 * (0.36 + 1.75), places=10)
        with tempfile.TemporaryDirectory() as tmp:
            res, led = os.path.join(tmp, "results.csv"), os.path.join(tmp, "runs.csv")
            rows = [{"run_id": "mu%d_extend+global+exact_50x150x50" % mu, "t_end": "1.0000", "steps": "9000",
                     "wall_s": "9999", "section_gradient": "%.1f" % (0.1 * mu + 50), "mean_gradient": "1.0",
                     "centroid_rise_mm": "1.00", "sharp_volume_change_pct": "1.20"} for mu in (100, 250, 1000)]
            rows.append(dict(rows[0], run_id="mu500_extend+global+exact_50x150x50", t_end="0.5000"))  # not at 1 s
            # The rigid bed on the approximate projection only: quoted, and said to be that projection.
            rows.append(dict(rows[0], run_id="rigid_50x150x50", section_gradient="18.0", mean_gradient="38.2"))
            write(res, *rows)
            write(led, dict(LEDGER, run_id="mu500_extend+global+exact_50x150x50"))
            out = script("cases/porous_bed/table.py", "--results", res, "--ledger", led,
                         "--packing", os.path.join(tmp, "none.json")).stdout
            self.assertIn("| 60.0 Pa/m | 75.0 Pa/m | *not finished*: wall_limit at t = 0.21 s", out)
            self.assertIn("*not run* | 150.0 Pa/m |", out)           # 750 Pa: in neither file
            self.assertIn("section-averaged gradient against mu_S (3 finished moduli", out)
            self.assertIn("0.1 Pa/m per Pa, intercept 50 Pa/m, R^2 = 1.000", out)
            self.assertIn("results.csv `rigid_50x150x50`, approximate projection, to t = 1 s): section-averaged "
                          "18.0 Pa/m, midline 38.2 Pa/m (9000 steps, 9999 s)", out)
            # With the case's packing.json: Ergun at its voidages, the gas of porous_bed.yaml.
            out = script("cases/porous_bed/table.py", "--results", res, "--ledger", led).stdout
            e = 0.4692954976092759   # packing.json voidage_written.interior
            self.assertIn("%.1f Pa/m (e = %.3f, interior)" % (ergun.gradient(e, **flow), e), out)

    def test_grid_cost_pairs_the_grids(self):
        # grid_cost.py: a modulus's finished runs on the two grids, of one model and tag only.
        grid_cost = load("cases/porous_bed/grid_cost.py", "porous_grid_cost")
        with tempfile.TemporaryDirectory() as tmp:
            res = os.path.join(tmp, "results.csv")
            base = {"t_end": "1.0000", "steps": "100", "wall_s": "1", "ranks": "1", "section_gradient": "50",
                    "centroid_rise_mm": "1"}
            ids = ["mu100_extend+global+exact_25x75x25", "mu100_extend+global+exact_50x150x50",
                   "mu250_extend+global+exact_50x150x50", "mu100_extend+global_50x150x50",
                   "mu100_integrate+global+exact_25x75x25", "mu500_extend+global+exact_20x60x20"]
            rows = [dict(base, run_id=i) for i in ids]
            rows.append(dict(base, run_id="mu750_extend+global+exact_25x75x25", t_end="0.5000"))  # unfinished
            write(res, *rows)
            got = grid_cost.sets(res, "extend", "+global+exact")
            self.assertEqual({mu: sorted(g) for mu, g in got.items()},
                             {100: ["25x75x25", "50x150x50"], 250: ["50x150x50"]})
            self.assertEqual(grid_cost.cells("25x75x25"), 46875)
            png = os.path.join(tmp, "cost.png")
            text = script("cases/porous_bed/grid_cost.py", "-o", png, "--results", res).stdout
            self.assertIn("| +global+exact | 100 | 25x75x25 | 4.69e+06 | 100 | 1 | 1 | 50 | 1 |", text)
            self.assertIn("| +global | 100 | 50x150x50 |", text)
            self.assertTrue(os.path.exists(png))

    def test_outlet_stats_reads_the_last_y_plane(self):
        # outlet.py: arrays are stored (z, y, x, 3); the outlet is the last y plane, backflow u_y < 0.
        try:
            import numpy as np
            outlet = load("cases/porous_bed/outlet.py")
        except ImportError:  # numpy, h5py: scripts/setup --figures
            self.skipTest("numpy/h5py")
        u = np.zeros((5, 4, 6, 3))         # outlet plane 5 x 6 nodes; its 3 x 4 inner ones are free
        u[1:-1, :, 1:-1, 1] = 0.1
        u[1, 2, 3] = (3.0, 4.0, 0.0)       # 5 m/s inside the duct
        u[1, -1, 1:3, 1] = -0.2            # 2 of the 12 free outlet nodes flow back
        u[3, -1, 4] = (0.0, 0.3, 0.4)      # the outlet's fastest: 0.5 m/s
        vmax, top, back = outlet.outlet_stats(u)
        self.assertEqual((vmax, top), (5.0, 0.5))
        self.assertAlmostEqual(back, 2 / 12, places=15)


if __name__ == "__main__":
    unittest.main()
