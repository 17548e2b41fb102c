"""cases/falling_block/table.py: the paper-vs-Voigt table quotes results.csv and, for runs not
finished, the ledger; with --readme it replaces only what lies between its markers."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

CASE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "cases", "falling_block")
RESULT = {"run_id": "mu1000_extend+global+exact_75", "steps": "3667", "wall_s": "5100", "ranks": "2",
          "slowing_s": "0.0607", "slowing_vy": "-0.535", "impact_gap_h": "0.52", "first_impact_s": "0.0597",
          "rebound_mm": "8.2", "rebound_to_s": "0.1267", "second_contact_s": "0.1465", "base_within_2h_s": "0.3288",
          "first_bending_peak_mm": "3.75", "first_bending_peak_s": "0.0803", "max_energy_ratio": "0.990"}
LEDGER = {"run_id": "mu2000_extend+global+exact_75", "state": "wall_limit", "t_reached": "0.21", "steps": "1500",
          "wall_s": "1200.5", "to_finish_s": "2000"}


def write(path, row):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(row))
        w.writeheader()
        w.writerow(row)


class TableTest(unittest.TestCase):
    def test_quotes_the_csvs_and_keeps_the_readme(self):
        with tempfile.TemporaryDirectory() as tmp:
            res, led, readme = (os.path.join(tmp, n) for n in ("results.csv", "runs.csv", "README.md"))
            write(res, RESULT)
            write(led, LEDGER)
            with open(readme, "w") as f:
                f.write("# before\n<!-- table.py: begin -->\nold table\n<!-- table.py: end -->\nafter\n")
            cmd = [sys.executable, os.path.join(CASE, "table.py"), "--results", res, "--ledger", led]
            subprocess.run(cmd + ["--readme", readme], check=True, capture_output=True)
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


if __name__ == "__main__":
    unittest.main()
