"""cases/falling_block's scripts on one tiny run of its scene: 16^3 cells to t = 0.1 s (about
110 steps, 1-2 s; the block falls onto the cylinder at ~0.06 s), fields every 0.02 s, its
probes (left, centre, right every 0.005 s, impact every 0.00025 s). block_track.py, plots.py
(and the events.py rules it prints), waves.py, render.py (VTK under xvfb; skipped without),
grid_cost.py (on results.csv rows made from plots.py's), wrinkles.py. table.py: test_case_tables.py."""
import csv
import os
import shutil
import tempfile
import unittest

from voigt_post import scene_record, series
from run_fixture import csv_rows, case_run, load, script

try:
    import numpy as np  # noqa: F401  (the scripts' numpy, h5py, matplotlib: scripts/setup --figures)
    import matplotlib  # noqa: F401
except ImportError:
    np = None

RUN = "mu1000_extend+global+exact_16"   # a study's run id: plots.py's results row is keyed by it


@unittest.skipIf(np is None, "numpy, matplotlib (scripts/setup --figures)")
class FallingBlock(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = case_run(RUN, "falling_block/falling_block.yaml", "domain.cells=[16,16,16]", end_time=0.1)
        cls.tmp = tempfile.mkdtemp(prefix="fb_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, True)

    def test_block_track(self):
        rows = csv_rows(script("cases/falling_block/block_track.py", self.out).stdout)
        self.assertEqual(list(rows[0]), ["t", "volume", "cx", "cy", "cz", "vx", "vy", "vz", "tilt_deg", "angle_z_deg",
                                         "bending", "gap_cylinder", "gap_base", "contact_cylinder", "contact_base"])
        self.assertEqual([round(float(r["t"]), 6) for r in rows], [0, 0.02, 0.04, 0.06, 0.08, 0.1])
        first = rows[0]
        self.assertAlmostEqual(float(first["cy"]), 0.075, delta=0.003)          # the scene's block centre
        self.assertAlmostEqual(float(first["volume"]), 0.06 * 0.02 * 0.06, delta=0.3 * 7.2e-5)
        # The gap to the scene's cylinder (its record: centre y 0.0375, r 0.01) under the block's face.
        self.assertAlmostEqual(float(first["gap_cylinder"]), 0.065 - 0.0475, delta=0.007)
        self.assertLess(float(rows[-1]["cy"]), float(first["cy"]))              # it fell
        sharp = csv_rows(script("cases/falling_block/block_track.py", self.out, "--cylinder", "0.049", "0.0375",
                                "0.01", "--sharp").stdout)
        self.assertEqual(len(sharp), len(rows))
        probes = csv_rows(script("cases/falling_block/block_track.py", self.out, "--probes").stdout)
        self.assertEqual(len(probes), 21)                                        # every 0.005 s to 0.1
        self.assertAlmostEqual(float(probes[0]["top_centre"]) - float(probes[0]["bottom_centre"]), 0.02, delta=0.007)
        self.assertNotEqual(script("cases/falling_block/block_track.py", check=False).returncode, 0)   # usage

    def test_wrinkles(self):
        rows = csv_rows(script("cases/falling_block/wrinkles.py", self.out).stdout)
        self.assertEqual(list(rows[0])[:9], ["run", "cells", "t", "top_mm", "bottom_mm", "bending_mm", "thickness_mm",
                                             "top_cells", "bottom_cells"])
        self.assertEqual(rows[0]["cells"], "16")
        self.assertEqual(round(float(rows[0]["t"]), 6), 0)
        # At t = 0 the faces are the superquadric's, flat to well under a cell over the window
        # (the 48^3 start: 0.01 cells; here 3 cells of thickness, the edges' rounding nearer).
        self.assertLess(float(rows[0]["top_cells"]), 0.1)
        shares = [float(rows[0][k]) for k in rows[0] if k.startswith("top_power_") and k.endswith("_mm")]
        self.assertAlmostEqual(sum(shares), 1.0, places=6)  # the wavelength bands cover the spectrum
        self.assertNotEqual(script("cases/falling_block/wrinkles.py", check=False).returncode, 0)   # usage

    def test_plots_row_and_digest(self):
        png, res, dig = (os.path.join(self.tmp, n) for n in ("d.png", "results.csv", "digests"))
        text = script("cases/falling_block/plots.py", "-o", png, "--run", self.out, "tiny", "--csv", res,
                      "--digests", dig).stdout
        self.assertTrue(os.path.getsize(png) > 1000)
        self.assertIn("| tiny | ", text)
        self.assertIn("| event | tiny |", text)                                   # events.py's table
        self.assertIn("plots.py: 1 finished run(s) merged into", text)
        with open(res) as f:
            row = next(csv.DictReader(f))
        self.assertEqual((row["run_id"], row["t_end"]), (RUN, "0.1000"))
        for key in ("slowing_s", "first_impact_s", "max_energy_ratio", "peak_bending_mm"):
            self.assertIn(key, row)
        npz = os.path.join(dig, RUN + ".npz")
        self.assertEqual(scene_record.scene(npz), scene_record.scene(self.out))
        again = script("cases/falling_block/plots.py", "-o", png, "--run", npz, "tiny").stdout
        table = lambda t: [x for x in t.splitlines() if x.startswith("|")]  # noqa: E731
        self.assertEqual(table(again), table(text))                              # the same tables from the digest

    def test_events_rules(self):
        ev = load("cases/falling_block/events.py", "fb_events")
        self.assertEqual(ev.slowing([0, 1, 2, 3], [0, -1.0, -2.0, -1.5]), (3, -2.0))
        self.assertIsNone(ev.slowing([0, 1], [0, -1.0]))
        cols = series.timeseries(self.out)
        m = ev.measure(cols, 0.1 / 16)
        self.assertEqual(m["t_end"], cols["t"][-1])
        self.assertEqual(len(ev.rows(m)), 11)

    def test_waves(self):
        png = os.path.join(self.tmp, "w.png")
        text = script("cases/falling_block/waves.py", "-o", png, "--run", self.out, "tiny",
                      "--window", "0.05", "0.1").stdout
        lines = [x for x in text.splitlines() if x.startswith("| tiny |")]
        self.assertTrue(lines)
        cs = series.summary(self.out)["elasticity"]["wave_speed"]
        self.assertTrue(all(" | %.2f | " % cs in x for x in lines))               # c_s from summary.json
        self.assertIn("| 4.90 |", lines[0])                                       # the source: the scene's cylinder top
        self.assertTrue(os.path.exists(png))

    def test_grid_cost(self):
        with open(os.path.join(self.tmp, "base.csv"), "w") as f:   # plots.py's row of this run
            script("cases/falling_block/plots.py", "-o", os.path.join(self.tmp, "g.png"), "--run", self.out, "x",
                   "--csv", f.name)
        with open(f.name) as f:
            row = next(csv.DictReader(f))
        res = os.path.join(self.tmp, "grid.csv")
        # As runs to 0.5 s: every panel's measure present (this one has not reached the base).
        rows = [dict(row, run_id="mu1000_%s+global+exact_%d" % (m, n), t_end="0.5000", steps=str(100 * n),
                     first_bending_peak_mm="3.1", base_within_2h_s="0.33")
                for m in ("extend", "integrate") for n in (30, 48)]
        series.write_csv(res, rows)
        png = os.path.join(self.tmp, "cost.png")
        text = script("cases/falling_block/grid_cost.py", "-o", png, "--results", res).stdout
        self.assertIn("| extend | 30^3 | 3000 |", text)
        self.assertIn("| integrate | 48^3 | 4800 |", text)
        self.assertTrue(os.path.exists(png))
        empty = os.path.join(self.tmp, "none.csv")
        series.write_csv(empty, [dict(row, t_end="0.1000")])                         # not at 0.5 s: nothing to draw
        r = script("cases/falling_block/grid_cost.py", "-o", png, "--results", empty, check=False)
        self.assertIn("no finished", r.stderr)

    @unittest.skipUnless(shutil.which("xvfb-run") or os.environ.get("DISPLAY"), "needs xvfb (scripts/setup --figures)")
    def test_render(self):
        png = os.path.join(self.tmp, "r.png")
        text = script("cases/falling_block/render.py", "-o", png, "--times", "0", "0.1", "--panel", "160", "120",
                      "--run", self.out, "tiny", "--cylinder", "0.049", "0.0375", "0.01").stdout
        self.assertIn("wrote", text)
        with open(png, "rb") as f:
            head = f.read(24)
        self.assertEqual(head[:8], b"\x89PNG\r\n\x1a\n")
        self.assertEqual(int.from_bytes(head[16:20], "big"), 2 * 160)


if __name__ == "__main__":
    unittest.main()
