"""Tests of voigt_post.series, fields, launch and report on the shared run (run_fixture.py):
what the readers return is checked against what the scene says and against each other (the
probe against the field, the Heaviside of Eq. (4) against the solver's own volume).
Standard library unittest; CTest runs it with python.voigt_post (numpy; h5py or h5dump)."""
import os
import shutil
import tempfile
import unittest

from voigt_post import fields, launch, report, series, xdmf
from voigt_post.formulas import heaviside
from run_fixture import CENTRE, H, RADIUS, RunFixture

try:
    import numpy as np
except ImportError:  # scripts/setup --figures installs python3-numpy
    np = None


class SeriesTest(RunFixture):
    def test_summary(self):
        s = series.summary(self.out)
        self.assertEqual(s["steps"], 8)                                   # 0.2 s / dt 0.025
        self.assertAlmostEqual(s["simulated_time"], 0.2, delta=1e-12)
        self.assertEqual(s["grid"]["cells"], [12, 8, 8])
        self.assertIsNone(series.summary(self.tmp, None))                 # no summary.json there
        with self.assertRaises(OSError):
            series.summary(self.tmp)
        half = tempfile.mkdtemp(dir=self.tmp)                             # a summary being written
        with open(os.path.join(half, "summary.json"), "w") as f:
            f.write('{"steps": 3, "simulated')
        self.assertEqual(series.summary(half, {}), {})
        with self.assertRaises(ValueError):
            series.summary(half)

    def test_timeseries(self):
        cols = series.timeseries(self.out)
        self.assertEqual(cols["step"], [float(i) for i in range(1, 9)])  # one row per step
        for i, t in enumerate(cols["t"]):
            self.assertAlmostEqual(t, 0.025 * (i + 1), delta=1e-6)       # CSV keeps 6 digits
        self.assertEqual(cols["dt"], [0.025] * 8)
        self.assertNotIn("dt_reason", cols)                              # text ("fixed")
        # a run still writing: a short last line is left out
        part = tempfile.mkdtemp(dir=self.tmp)
        with open(os.path.join(self.out, "timeseries.csv")) as f:
            text = f.read()
        with open(os.path.join(part, "timeseries.csv"), "w") as f:
            f.write(text + "9,0.225,0.0")
        self.assertEqual(series.timeseries(part)["step"], cols["step"])

    def test_probe_matches_the_field(self):
        p = series.probe(self.out, "axis")
        self.assertEqual(sorted(p), [0.0, 0.1, 0.2])                     # probe interval 0.1
        rows = p[0.0]
        self.assertEqual([round(r["x"], 9) for r in rows], [0.0625 + H * i for i in range(12)])
        if np is None:
            return
        # The points are x cell centres on the faces y = z = 0.5 between cells 3 and 4: the
        # probe's interpolation is the mean of those four cells, to rounding (the CSV has 17 digits).
        psi = fields.read(xdmf.frames(self.out)[0].path, "psi")
        for i, r in enumerate(rows):
            self.assertAlmostEqual(r["psi"], psi[3:5, 3:5, i].mean(), delta=1e-15)
        arr = series.probe_array((self.out, "axis"))
        self.assertEqual(len(arr), 3 * 12)
        self.assertEqual(list(arr["psi"][:12]), [r["psi"] for r in rows])

    def test_csv_round_trip(self):
        path = os.path.join(tempfile.mkdtemp(dir=self.tmp), "t.csv")
        series.write_csv(path, [{"a": 1, "b": 2}, {"a": 3, "c": "x"}])    # columns as first seen
        self.assertEqual(series.read_csv(path), [{"a": "1", "b": "2", "c": ""}, {"a": "3", "b": "", "c": "x"}])

    def test_merge_csv(self):
        # results.csv: a rerun's row replaces its old one in place, rows of runs whose outputs
        # are gone stay, new runs and new columns go last.
        path = os.path.join(tempfile.mkdtemp(dir=self.tmp), "r.csv")
        series.merge_csv(path, [{"run_id": "a", "x": 1}, {"run_id": "b", "x": 2}])
        series.merge_csv(path, [{"run_id": "c", "x": 5, "y": 7}, {"run_id": "a", "x": 3, "y": 4}])
        self.assertEqual(series.read_csv(path), [{"run_id": "a", "x": "3", "y": "4"}, {"run_id": "b", "x": "2", "y": ""},
                                                 {"run_id": "c", "x": "5", "y": "7"}])
        series.merge_csv(path, [{"run_id": "b", "x": 8}, {"run_id": "b", "x": 9}])  # the last of equal ids wins
        self.assertEqual([r["x"] for r in series.read_csv(path)], ["3", "9", "5"])


@unittest.skipIf(np is None, "needs numpy")
class FieldsTest(RunFixture):
    def test_shapes_and_names(self):
        path = xdmf.frames(self.out)[-1].path
        self.assertEqual(fields.names(path), ["psi", "velocity"])        # output.fields
        self.assertEqual(fields.read(path, "psi").shape, (8, 8, 12))      # cells, z y x
        self.assertEqual(fields.read(path, "/velocity").shape, (9, 9, 13, 3))   # nodes, 3 components
        self.assertEqual(fields.mid_z(path, "psi").shape, (8, 12))

    def test_initial_psi_is_the_signed_distance(self):
        psi = fields.read(xdmf.frames(self.out)[0].path, "psi")
        z, y, x = np.meshgrid(*[(np.arange(n) + 0.5) * H for n in psi.shape], indexing="ij")
        d = RADIUS - np.sqrt((x - CENTRE[0]) ** 2 + (y - CENTRE[1]) ** 2 + (z - CENTRE[2]) ** 2)
        self.assertLess(np.abs(psi - d).max(), 1e-12)                    # the sphere, positive inside

    def test_heaviside_gives_the_solvers_volume(self):
        # sum H(psi) h^3 with kappa = smoothing_cells h is the level set's volume (summary.json,
        # kernels/heaviside.hpp in C++): equal to rounding (sums of 768 terms: ~1e-15 relative)
        s = series.summary(self.out)
        psi = fields.read(xdmf.frames(self.out)[0].path, "psi")
        kappa = s["level_set"]["smoothing_cells"] * H
        vol = float(heaviside(psi, kappa).sum()) * H ** 3
        self.assertAlmostEqual(vol / s["level_set"]["volume_initial"], 1.0, delta=1e-13)
        self.assertEqual(float((psi > 0).sum()) * H ** 3, s["level_set"]["sharp_volume_initial"])

    @unittest.skipUnless(shutil.which("h5dump") and shutil.which("h5ls"), "needs hdf5-tools")
    def test_h5dump_reads_the_same_doubles(self):
        path = xdmf.frames(self.out)[-1].path
        with_h5py = [fields.read(path, n) for n in ("psi", "velocity")]
        keep = fields._h5py
        fields._h5py = lambda: None                                      # as without python3-h5py
        try:
            without = [fields.read(path, n) for n in ("psi", "velocity")]
            self.assertEqual(fields.names(path), ["psi", "velocity"])
        finally:
            fields._h5py = keep
        for a, b in zip(with_h5py, without):
            self.assertEqual(a.shape, b.shape)
            self.assertTrue((a == b).all())


class LaunchTest(unittest.TestCase):
    def test_command_lines(self):
        cmd = launch.voigt_cmd("v", "s.yaml", "out", ["a=1", "b=[2,3]"], steps=5)
        self.assertEqual(cmd, ["v", "run", "s.yaml", "-o", "out", "--overwrite", "--steps", "5",
                               "--set", "a=1", "--set", "b=[2,3]"])
        self.assertEqual(launch.voigt_cmd("v", "s", "o", overwrite=False), ["v", "run", "s", "-o", "o"])
        mpi = launch.voigt_cmd("v", "s", "o", ranks=2, end_time=0.055, restart_from="c.h5")
        self.assertEqual(mpi[:mpi.index("-np") + 2], launch.MPIRUN + ["2"])
        for flag in ("--allow-run-as-root", "--oversubscribe"):               # containers, 2 cores
            self.assertIn(flag, mpi)
        self.assertEqual(mpi[-4:], ["--end-time", "0.055", "--restart-from", "c.h5"])

    def test_run_logged_and_tail(self):
        tmp = tempfile.mkdtemp(prefix="voigt_post_")
        self.addCleanup(shutil.rmtree, tmp, True)
        log = os.path.join(tmp, "log")
        rc, secs = launch.run_logged(["sh", "-c", "echo hello; echo oops >&2; exit 3"], log, 60)
        self.assertEqual(rc, 3)
        self.assertEqual(launch.tail(log), "hello\noops\n")               # stdout and stderr
        self.assertEqual(launch.tail(log, 5), "oops\n")
        self.assertEqual(launch.tail(os.path.join(tmp, "none")), "")
        rc, secs = launch.run_logged(["sleep", "30"], log, 1)
        self.assertEqual(rc, "timeout after 1 s")
        self.assertLess(secs, 20)                                         # killed, not waited for


def text(path):
    with open(path) as f:
        return f.read()


class ReportTest(unittest.TestCase):
    def test_numbers(self):
        self.assertEqual([report.fmt(x) for x in (None, 0, 1.23456, 12345.6)], ["-", "0", "1.235", "1.23e+04"])
        self.assertEqual(report.med([3, None, 1, 2]), 2)
        self.assertIsNone(report.med([None]))
        self.assertEqual(report.spread([2.0, None, 0.5]), "0.5-2")
        self.assertEqual(report.spread([]), "-")

    def test_replace_section(self):
        path = os.path.join(tempfile.mkdtemp(prefix="voigt_post_"), "README.md")
        self.addCleanup(shutil.rmtree, os.path.dirname(path), True)
        b, e = "<!-- BEGIN -->", "<!-- END -->"
        report.replace_section(path, b, e, ["one"], "Title")            # a new file
        self.assertEqual(text(path), "# Title\n\n%s\none\n%s\n" % (b, e))
        with open(path, "a") as f:
            f.write("after\n")
        report.replace_section(path, b, e, ["two", "three"], "Title")   # text around it kept
        self.assertEqual(text(path), "# Title\n\n%s\ntwo\nthree\n%s\nafter\n" % (b, e))


if __name__ == "__main__":
    unittest.main()
