"""perf/compare.py (perf/compare) and perf/compare_lib.py. A comparison builds two revisions and
runs full-size scenes (tens of minutes), so the test runs its command line as far as it goes
without building (the options' checks, an unknown revision) and its data-reading and report
functions on the shared tiny run's summary.json (run_fixture.py), taken as both A and B."""
import json
import os
import unittest

from run_fixture import RunFixture, load, script


class PerfCompare(RunFixture):
    def test_command_line(self):
        self.assertIn("perf/compare REV", script("perf/compare.py", "--help").stdout)
        r = script("perf/compare.py", "HEAD", "--scenes", "cavity,nowhere", check=False)
        self.assertEqual(r.returncode, 2)
        self.assertIn("unknown scene 'nowhere'", r.stderr)
        r = script("perf/compare.py", "no-such-revision-xyz", check=False)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("git rev-parse", r.stderr)

    def test_metrics_and_report(self):
        L = load("perf/compare_lib.py", "compare_lib")
        with open(os.path.join(self.out, "summary.json")) as f:
            summ = json.load(f)
        m = L.metrics(summ)
        self.assertEqual(m["steps"], 8)
        self.assertAlmostEqual(m["s_per_step"], summ["wall_seconds"] / 8)
        self.assertIn("projection", m["stages"])
        key = ("carried", 1, 8)
        runs = [{"rev": rev, "ok": True, "key": key, "metrics": m} for rev in ("A", "B", "A", "B")]
        agg = {key: L.aggregate(runs, key)}
        self.assertEqual(agg[key]["A"]["times"], [m["s_per_step"]] * 2)
        ident = {"sha": "0" * 40, "short": "0000000", "describe": "d", "subject": "s", "changed_files": [],
                 "diff_stat": ""}
        meta = {"A": ident, "B": ident, "date": "today", "nproc": 2, "load_start": "0", "load_end": "0",
                "settings_text": "projection best", "repeats": 2, "window_text": "first steps", "a_bin": "a",
                "b_bin": "b", "build_a_s": 0, "build_b_s": 0, "runs_s": 1, "total_s": 1}
        text = L.report(meta, [key], agg, runs)
        self.assertIn("| carried | 1 | 8 |", text)
        self.assertIn("| **1.000** | within noise |", text)               # the same run as A and B
        self.assertIn("### carried, 1 rank, 8 steps", text)


if __name__ == "__main__":
    unittest.main()
