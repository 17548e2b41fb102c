"""The long runs' ledger (voigt_post/ledger.py, run_ids.py) and its command line cases/runs.py:
what a fresh machine (no outputs) learns from it."""
import csv
import json
import os
import tempfile
import unittest

from voigt_post import ledger as runs
from voigt_post import run_ids
from run_fixture import script


class Ledger(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.ledger = os.path.join(self.dir.name, "runs.csv")

    def tearDown(self):
        self.dir.cleanup()

    def test_unfinished_in_words(self):
        row = {"state": "wall_limit", "t_reached": "0.62", "steps": "6388", "wall_s": "2932.2", "to_finish_s": "1404"}
        self.assertEqual(runs.unfinished(row),
                         "*not finished*: wall_limit at t = 0.62 s (6388 steps, 2932.2 s); to finish ~1404 s")
        # A first segment still running: no wall time yet, and no empty "s" in its place.
        row = {"state": "running", "t_reached": "0.1", "steps": "1200", "wall_s": "", "to_finish_s": ""}
        self.assertEqual(runs.unfinished(row), "*not finished*: running at t = 0.1 s (1200 steps)")
        self.assertEqual(runs.unfinished({"state": "running", "t_reached": ""}), "*not finished*: running, no checkpoint yet")

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
            rows = {r["run_id"]: r for r in csv.DictReader(f)}
        self.assertEqual((rows["a"]["steps"], rows["a"]["t_reached"], rows["a"]["state"]), ("2", "0.2", "running"))
        self.assertEqual(rows["b"]["steps"], "")
        self.assertEqual(rows["c"]["steps"], "9")

    def test_end_records_what_finishing_costs(self):
        # Issue 22 item 5: a run stopped at its wall limit says what finishing it costs at its
        # last segment's pace. Here 0.3 s left at a mean dt of 0.01 s (last 100 steps: the
        # 0.05 s steps before them do not count) is 30 steps at 20 s / 40 steps = 0.5 s each.
        d = os.path.join(self.dir.name, "r")
        os.makedirs(d)
        with open(os.path.join(d, "timeseries.csv"), "w") as f:
            f.write("step,t,dt,dt_reason\n")
            f.writelines("%d,0,%g,cfl\n" % (k, 0.05 if k < 10 else 0.01) for k in range(110))
        record = "# The scene this run segment used, as Voigt ran it (segment 1):\n# s.yaml\n%sname: s\n" \
                 "domain:\n  cells: [4, 4, 4]\ntime:\n  cfl: 0.5\n  end: 0.5\nlevel_set:\n  end: 9\n"
        summ = {"state": "wall_limit", "simulated_time": 0.2, "steps": 110, "steps_this_run": 40,
                "wall_seconds": 20.0, "wall_seconds_total": 55.0}
        # The end time from: the run's scene record (time.end, not another map's end), its
        # --end-time line, summary.json's end_time (Voigt since 2026-12-04).
        for head, extra, left in (("", {}, "15"), ("# --end-time 0.3\n", {}, "5"), ("", {"end_time": 0.8}, "30")):
            with open(os.path.join(d, "scene.yaml"), "w") as f:
                f.write(record % head)
            with open(os.path.join(d, "summary.json"), "w") as f:
                json.dump(dict(summ, **extra), f)
            runs.end(self.ledger, "r", d, 75, 0)
            row = next(csv.DictReader(open(self.ledger)))
            self.assertEqual((row["state"], row["to_finish_s"], row["wall_s"]), ("wall_limit", left, "55.0"))
        script("cases/runs.py", "start", self.ledger, "r", "1000", "m", "4x4x4", "1")  # a new segment: unknown
        self.assertEqual(next(csv.DictReader(open(self.ledger)))["to_finish_s"], "")
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump(dict(summ, state="finished", simulated_time=0.8, end_time=0.8), f)
        runs.end(self.ledger, "r", d, 0, 0)
        self.assertEqual(next(csv.DictReader(open(self.ledger)))["to_finish_s"], "0")
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump(dict(summ, state="blow_up", end_time=0.8), f)
        runs.end(self.ledger, "r", d, 1, 0)  # a blow-up cannot be finished
        self.assertEqual(next(csv.DictReader(open(self.ledger)))[("state")], "failed")
        self.assertEqual(next(csv.DictReader(open(self.ledger)))["to_finish_s"], "")

    def test_end_records_the_builds_of_each_segment(self):
        # summary.json's segment_history (Voigt since 2026-12-05): the ledger names the builds
        # in the order they ran, a repeat once; "?" for segments from before the record.
        d = os.path.join(self.dir.name, "r")
        os.makedirs(d)
        hist = [{"segments": 2, "revision": None}, {"revision": "aaa"}, {"revision": "aaa"}, {"revision": "bbb-dirty"}]
        for h, want in ((hist, "? aaa bbb-dirty"), (hist[1:3], "aaa"), ([], "")):
            with open(os.path.join(d, "summary.json"), "w") as f:
                json.dump({"state": "finished", "simulated_time": 1, "steps": 5, "wall_seconds": 1.0,
                           "segment_history": h}, f)
            runs.end(self.ledger, "r", d, 0, 0)
            self.assertEqual(next(csv.DictReader(open(self.ledger)))["revisions"], want)

    def test_run_id_says_which_projection(self):
        scene = os.path.join(self.dir.name, "s.yaml")
        for body, sets, tag in [("projection:\n  operator: approximate\n  tolerance: 1e-6\n", [], "+settled+surface"),
                                ("projection:\n  # note\n\n  operator: exact\n", [], "+exact+balanced+settled+surface"),
                                ("time: {end: 1}\n", [], "+exact+balanced+settled+surface"),  # Voigt's default operator
                                ("projection:\n  tolerance: 1e-3\nother:\n  operator: approximate\n", [], "+exact+balanced+settled+surface"),
                                ("projection:\n  operator: approximate\n", ["projection.operator=exact"], "+exact+balanced+settled+surface"),
                                ("time: {end: 1}\n", ["projection.hydrostatic=none"], "+exact+settled+surface"),  # issue 50 off
                                ("time: {end: 1}\n", ["reinit.zone_tolerance=0"], "+exact+balanced+surface"),
                                ("time: {end: 1}\n", ["level_set.surface_velocity=flow"], "+exact+balanced+settled"),  # issue 53 off
                                ("projection:\n  operator: exact\n", ["projection.operator=approximate"], "+settled+surface")]:
            with open(scene, "w") as f:
                f.write("domain:\n  cells: [4, 8, 4]\n" + body)
            self.assertEqual(run_ids.tagged_model("extend", sets, scene), "extend+global" + tag, body)
        self.assertEqual(run_ids.run_id("100", run_ids.tagged_model("extend", [], scene), "4x8x4"), "mu100_extend+global+exact+balanced+settled+surface_4x8x4")
        self.assertEqual(run_ids.tagged_model("extend", ["level_set.volume_correction=none"]), "extend+none+settled+surface")

    def test_durations(self):
        for text, s in [("3h", 10800), ("170m", 10200), ("3600s", 3600), ("02:50:00", 10200)]:
            self.assertAlmostEqual(run_ids.seconds(text), s)
        with self.assertRaises(ValueError):
            run_ids.seconds("soon")


    def test_command_line(self):
        # cases/runs.py, as cases/study.sh and the run scripts call it.
        scene = os.path.join(self.dir.name, "s.yaml")
        with open(scene, "w") as f:
            f.write("domain:\n  cells: [4, 8, 4]\nprojection:\n  operator: approximate\n")
        run = lambda *a, **k: script("cases/runs.py", *a, **k).stdout  # noqa: E731
        self.assertEqual(run("id", scene, "100", "extend", "domain.cells=[6,6,6]"),
                         "mu100_extend+global+settled+surface_6 6x6x6 extend+global+settled+surface\n")
        self.assertEqual(run("seconds", "2h30m"), "9000\n")
        self.assertIn("is not a duration", script("cases/runs.py", "seconds", "soon", check=False).stderr)
        self.assertEqual(run("state", self.dir.name), "new\n")
        self.assertEqual(run("recorded", self.ledger, "a"), "\n")
        run("start", self.ledger, "a", "100", "extend+global", "4x8x4", "2")
        self.assertEqual(run("recorded", self.ledger, "a"), "running\n")
        table = run("table", self.ledger).splitlines()
        self.assertEqual(table[0], "| " + " | ".join(runs.COLUMNS) + " |")
        self.assertTrue(table[2].startswith("| a | 100 | extend+global | 4x8x4 | 2 |"))
        d = os.path.join(self.dir.name, "a")
        os.makedirs(d)
        with open(os.path.join(d, "summary.json"), "w") as f:
            json.dump({"state": "finished", "simulated_time": 0.5, "steps": 7, "wall_seconds": 2.0}, f)
        run("end", self.ledger, "a", d, "0", "0")
        self.assertEqual(run("recorded", self.ledger, "a"), "finished\n")
        self.assertEqual(run("progress", self.ledger, self.dir.name), "")   # nothing running
        self.assertNotEqual(script("cases/runs.py", "nonsense", check=False).returncode, 0)


if __name__ == "__main__":
    unittest.main()
