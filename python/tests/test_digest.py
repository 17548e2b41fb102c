"""voigt_post/digest.py: a run's digest stands in for its folder wherever the readers take one
(series, scene_record, picture), holds its small files exactly, cuts probes to a window, and
keeps psi and a colour around the surface at chosen times. On the shared run (run_fixture.py:
a sphere of radius 0.25 in 12 x 8 x 8 cells, outputs at t = 0, 0.1, 0.2, probe `axis`)."""
import os
import unittest

from voigt_post import digest, fields, scene_record, series, xdmf
from run_fixture import H, RunFixture

try:
    import numpy as np
except ImportError:  # a --figures package
    np = None
try:
    import vtk  # noqa: F401
except ImportError:
    vtk = None


@unittest.skipIf(np is None, "numpy (scripts/setup --figures)")
class DigestTest(RunFixture):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.dig = os.path.join(cls.tmp, "carried.npz")
        # 0.12 is nearest the output at 0.1, as 0.1 itself: kept once.
        digest.write(cls.out, cls.dig, times=(0.1, 0.12, 0.2), field="velocity", probes={"axis": (0.05, 0.15)})

    def test_small_files_exactly(self):
        self.assertFalse(os.path.exists(self.dig + ".part"))
        self.assertEqual(series.summary(self.dig), series.summary(self.out))
        self.assertEqual(series.timeseries(self.dig), series.timeseries(self.out))
        self.assertEqual(scene_record.scene(self.dig), scene_record.scene(self.out))
        self.assertEqual(digest.run_id(self.dig), "carried")
        self.assertEqual(series.run_row(self.dig, series.summary(self.dig))["run_id"], "carried")
        self.assertTrue(series.has(self.dig, "probe_axis.csv"))
        self.assertFalse(series.has(self.dig, "probe_none.csv"))
        with self.assertRaises(OSError):
            series.probe(self.dig, "none")

    def test_probe_cut_to_its_window(self):
        whole, cut = series.probe(self.out, "axis"), series.probe(self.dig, "axis")
        self.assertEqual(sorted(whole), [0.0, 0.1, 0.2])   # the fixture's probe times
        self.assertEqual(cut, {0.1: whole[0.1]})
        self.assertEqual(len(series.probe_array((self.dig, "axis"))), 12)
        other = os.path.join(self.tmp, "no_probes.npz")
        digest.write(self.out, other, probes={})
        self.assertFalse(series.has(other, "probe_axis.csv"))
        self.assertEqual(digest.frames(other), [])

    def test_frames_hold_the_surface(self):
        fr = digest.frames(self.dig)
        full = xdmf.frames(self.out)
        self.assertEqual([f.t for f in fr], [full[1].t, full[2].t])
        for f, g in zip(fr, full[1:]):
            self.assertEqual((f.cells, f.origin, f.spacing, f.field), (g.cells, g.origin, g.spacing, "velocity"))
            psi = fields.read(g.path, "psi")
            vel = np.linalg.norm(fields.read(g.path, "velocity"), axis=-1)
            start = [int(round((c - o) / s)) for c, o, s in zip(f.crop_origin, f.origin, f.spacing)][::-1]
            box = tuple(slice(a, a + n) for a, n in zip(start, f.psi.shape))
            outside = np.ones(psi.shape, bool)
            outside[box] = False
            # Nothing within PAD cells of the surface is cut away ...
            self.assertTrue(np.all(psi[outside] < -digest.PAD * H))
            # ... and inside the band psi and the colour are the field's to float16 (10-bit mantissa).
            band = np.abs(psi[box]) <= digest.PAD * H
            self.assertTrue(band.any())
            np.testing.assert_allclose(f.psi[band], psi[box][band], rtol=2e-3, atol=1e-6 * H)
            np.testing.assert_allclose(f.colour[band], vel[box][band], rtol=2e-3, atol=1e-9)

    @unittest.skipIf(vtk is None, "python3-vtk9 (scripts/setup --figures)")
    def test_surface_as_from_the_folder(self):
        from voigt_post import picture
        f, g = digest.frames(self.dig)[0], xdmf.frames(self.out)[1]
        a = picture.surface(*picture._arrays(f, "velocity"), f.spacing, "velocity")
        b = picture.surface(*picture._arrays(g, "velocity"), g.spacing, "velocity")
        from vtk.util import numpy_support as ns
        pa, pb = (ns.vtk_to_numpy(s.GetPoints().GetData()) for s in (a, b))
        self.assertEqual(pa.shape, pb.shape)
        self.assertGreater(len(pa), 50)
        # Points move by psi's float16 rounding: ~1e-3 of PAD h over a gradient of ~1.
        self.assertLess(np.abs(pa - pb).max(), 1e-2 * H)
        ca, cb = (ns.vtk_to_numpy(s.GetPointData().GetScalars()) for s in (a, b))
        np.testing.assert_allclose(ca, cb, rtol=1e-2, atol=1e-6)


if __name__ == "__main__":
    unittest.main()
