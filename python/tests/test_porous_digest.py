"""The porous bed's scripts on two 10 x 30 x 10 runs of the porous bed and one of its rigid bed
to t = 0.03 s (about 1 s each): plots.py (voigt_post/porous_bed.py: a run's digest gives the
same numbers as its folder, Figs. 4-6, the table and results.csv row, so figures outlive the
machine a run was on), outlet.py and band_speeds.py. VOIGT names the binary."""
import os
import shutil
import subprocess
import tempfile
import unittest

from voigt_post import scene_record
from run_fixture import PYTHON, REPO, script

CASE = os.path.join(REPO, "cases", "porous_bed")
try:
    import numpy as np
    from voigt_post import porous_bed as run_data
except ImportError:  # numpy is a --figures package
    np = None


@unittest.skipIf(np is None, "numpy (scripts/setup --figures)")
class Digest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        voigt = os.environ.get("VOIGT", os.path.join(REPO, "build", "voigt"))
        cls.runs = []
        for mu in (100, 1000):
            d = os.path.join(cls.tmp.name, "mu%d_extend+global+exact_10x30x10" % mu)
            subprocess.run([voigt, "run", os.path.join(CASE, "porous_bed.yaml"), "-o", d, "--end-time", "0.03",
                            "--set", "domain.cells=[10,30,10]", "--set", "output.interval=0.01",
                            "--set", "probes.0.interval=0.01", "--set", "materials.bed.shear_modulus=%d" % mu],
                           check=True, capture_output=True)
            cls.runs.append((mu, d))
        # The rigid bed (rigid_bed.py: the spheres as fixed obstacles, no level set) on the same grid.
        scene = os.path.join(cls.tmp.name, "rigid.yaml")
        with open(scene, "w") as f:
            subprocess.run([PYTHON, os.path.join(CASE, "rigid_bed.py"), "--approximate"], check=True, stdout=f)
        cls.rigid = os.path.join(cls.tmp.name, "rigid_10x30x10")
        subprocess.run([voigt, "run", scene, "-o", cls.rigid, "--end-time", "0.03", "--set", "domain.cells=[10,30,10]",
                        "--set", "output.interval=0.01", "--set", "probes.0.interval=0.01"], check=True, capture_output=True)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def plots(self, tag, sources, extra=()):
        out = os.path.join(self.tmp.name, tag)
        args = ["-o", out, "--csv", out + ".csv"] + list(extra)
        for mu, src in sources:
            args += ["--run", src, str(mu)]
        text = script("cases/porous_bed/plots.py", *args).stdout
        with open(out + ".csv") as f:
            return text.replace(out, "OUT"), f.read()

    def test_digest_gives_the_folder_numbers(self):
        dig = os.path.join(self.tmp.name, "digests")
        table_dir, csv_dir = self.plots("from_dirs", self.runs, ["--digests", dig])
        sources = [(mu, os.path.join(dig, os.path.basename(d) + ".npz")) for mu, d in self.runs]
        for (_, d), (_, path) in zip(self.runs, sources):
            self.assertTrue(os.path.exists(path), path)
            self.assertLess(os.path.getsize(path), 200_000)  # small enough to commit
            self.assertEqual(scene_record.scene(path), scene_record.scene(d))   # the scene record too
        table_dig, csv_dig = self.plots("from_digests", sources)
        self.assertEqual(table_dir, table_dig)  # every printed number, from doubles
        self.assertEqual(csv_dir, csv_dig)      # the results.csv rows
        # Slices are float32 (colour maps): equal to the field's to single precision.
        a, b = run_data.RunDir(self.runs[0][1]).slices(), run_data.Digest(sources[0][1]).slices()
        self.assertEqual(list(a[0]), list(b[0]))
        for (ta, pa, sa), (tb, pb, sb) in zip(a[1], b[1]):
            self.assertEqual(ta, tb)
            np.testing.assert_allclose(pb, pa, rtol=1e-6, atol=1e-6 * np.abs(pa).max())
            np.testing.assert_allclose(sb, sa, rtol=1e-6, atol=1e-6 * np.abs(sa).max())

    def test_rigid_bed_row_and_digest(self):
        # plots.py --rigid: the rigid run's results.csv row (model "rigid", no modulus, no centroid)
        # and its digest (midline and section only), which gives the same printed numbers; a second
        # call leaves the digests as they are (an .npz rewritten would differ by its time stamps).
        dig = os.path.join(self.tmp.name, "rigid_digests")
        text_dir, csv_dir = self.plots("rigid_dirs", self.runs[:1], ["--rigid", self.rigid, "--digests", dig])
        rows = {r.split(",")[0]: r.split(",") for r in csv_dir.splitlines()}
        head = rows["run_id"]
        rigid = dict(zip(head, rows["rigid_10x30x10"]))
        self.assertEqual((rigid["model"], rigid["mu_S"], rigid["centroid_rise_mm"]), ("rigid", "", ""))
        path = os.path.join(dig, "rigid_10x30x10.npz")
        z = np.load(path)
        self.assertNotIn("centroid_cy", z.files)
        stamps = {n: os.path.getmtime(os.path.join(dig, n)) for n in os.listdir(dig)}
        self.plots("rigid_again", self.runs[:1], ["--rigid", self.rigid, "--digests", dig])
        self.assertEqual(stamps, {n: os.path.getmtime(os.path.join(dig, n)) for n in os.listdir(dig)})
        text_dig, _ = self.plots("rigid_digest", self.runs[:1], ["--rigid", path])
        line = [x for x in text_dir.splitlines() if x.startswith("rigid bed")]
        self.assertEqual(len(line), 1)
        self.assertIn(line[0], text_dig)

    def test_outlet(self):
        text = script("cases/porous_bed/outlet.py", self.runs[0][1], self.runs[1][1]).stdout.splitlines()
        self.assertEqual(len(text), 6)                                            # three lines per run
        self.assertRegex(text[0], r"^mu100_extend\+global\+exact_10x30x10: \d+ steps, section gradient -?[\d.]+ Pa/m, "
                                  r"centroid rise -?[\d.]+ mm$")
        self.assertEqual(text[2].count("/"), 2 * 4)                               # outputs at t = 0, 0.01, 0.02, 0.03
        self.assertNotEqual(script("cases/porous_bed/outlet.py", check=False).returncode, 0)   # usage

    def test_band_speeds(self):
        # The bed's last output and the rigid bed's (no psi: the packing's spheres stand in);
        # the grid, densities and smoothing from the scene record beside the file.
        for run, what in ((self.runs[0][1], "psi"), (self.rigid, "spheres")):
            path = sorted(f for f in os.listdir(run) if f.startswith("fields_"))[-1]
            r = script("cases/porous_bed/band_speeds.py", os.path.join(run, path))
            head, rows = r.stdout.splitlines()[0], [x for x in r.stdout.splitlines() if x.startswith("| (")]
            self.assertRegex(head, r"bed interior, \d+ nodes; max speed [\d.e+-]+ m/s$", what)
            self.assertTrue(rows, what)
            self.assertEqual(sum(int(x.split(" | ")[1]) for x in rows), int(head.split("bed interior, ")[1].split()[0]))
            self.assertNotIn("no scene record", r.stderr)
        # A file copied out of its run: read as the case's scene (the paper's grid), said on stderr.
        alone = os.path.join(self.tmp.name, "alone.h5")
        shutil.copy(os.path.join(self.runs[0][1], "fields_000000.h5"), alone)
        r = script("cases/porous_bed/band_speeds.py", alone, check=False)
        self.assertIn("no scene record", r.stderr)

    def test_digest_refuses_a_time(self):
        d = os.path.join(self.tmp.name, "x.npz")
        run_data.write_digest(run_data.RunDir(self.runs[0][1]), d)
        with self.assertRaises(SystemExit):
            run_data.load(d, at=0.01)


if __name__ == "__main__":
    unittest.main()
