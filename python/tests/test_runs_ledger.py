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

    def test_progress_records_the_last_checkpoint_of_running_rows(self):
        out = os.path.join(self.dir.name, "out")
        os.makedirs(os.path.join(out, "a"))
        with open(os.path.join(out, "a", "timeseries.csv"), "w") as f:
            f.write("step,t,dt\n1,0.1,0.1\n2,0.2,0.1\n3,0.3,0.1\n")
        with open(os.path.join(out, "a", "latest"), "w") as f:
            f.write("checkpoint_000000002.h5\n")  # step 3 has no checkpoint yet
        runs.update(self.ledger, "a", {"state": "running"})
        runs.update(self.ledger, "b", {"state": "running"})  # no output here: left alone
        runs.update(self.ledger, "c", {"state": "finished", "steps": "9"})
        self.assertEqual(runs.progress(self.ledger, out), ["a"])
        with open(self.ledger) as f:
            rows = {r["run_id"]: r for r in runs.csv.DictReader(f)}
        self.assertEqual((rows["a"]["steps"], rows["a"]["t_reached"], rows["a"]["state"]), ("2", "0.2", "running"))
        self.assertEqual(rows["b"]["steps"], "")
        self.assertEqual(rows["c"]["steps"], "9")

    def test_durations(self):
        for text, s in [("3h", 10800), ("170m", 10200), ("3600s", 3600), ("02:50:00", 10200)]:
            self.assertAlmostEqual(runs.seconds(text), s)
        with self.assertRaises(ValueError):
            runs.seconds("soon")


if __name__ == "__main__":
    unittest.main()
