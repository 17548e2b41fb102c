"""cases/runs.py, the long runs' ledger: what a fresh machine (no outputs) learns from it."""
import importlib.util
import json
import os
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
SPEC = importlib.util.spec_from_file_location(
    "runs", os.path.join(HERE, "..", "..", "cases", "runs.py"))
runs = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(runs)


class Ledger(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.ledger = os.path.join(self.dir.name, "runs.csv")

    def tearDown(self):
        self.dir.cleanup()

    def test_recorded_state_survives_without_outputs(self):
        self.assertEqual(runs.recorded(self.ledger, "a"), "")  # no ledger yet
        runs.update(self.ledger, "a", {"modulus": "1000", "state": "running"})
        runs.update(self.ledger, "b", {"modulus": "2000", "state": "wall_limit"})
        runs.update(self.ledger, "a", {"state": "finished"})
        self.assertEqual(runs.recorded(self.ledger, "a"), "finished")
        self.assertEqual(runs.recorded(self.ledger, "b"), "wall_limit")
        self.assertEqual(runs.recorded(self.ledger, "c"), "")
        # An output folder that is not on this machine is "new", whatever the ledger says.
        self.assertEqual(runs.state(os.path.join(self.dir.name, "a")), "new")

    def test_state_from_outputs(self):
        d = os.path.join(self.dir.name, "r")
        os.makedirs(d)
        self.assertEqual(runs.state(d), "new")
        open(os.path.join(d, "latest"), "w").close()
        self.assertEqual(runs.state(d), "unfinished")
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump({"state": "finished"}, f)
        self.assertEqual(runs.state(d), "finished")
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump({"state": "blow_up"}, f)
        self.assertEqual(runs.state(d), "failed")

    def test_durations(self):
        for text, s in [("3h", 10800), ("170m", 10200), ("3600s", 3600), ("02:50:00", 10200)]:
            self.assertAlmostEqual(runs.seconds(text), s)
        with self.assertRaises(ValueError):
            runs.seconds("soon")


if __name__ == "__main__":
    unittest.main()
