"""Tests of voigt_post.formulas and voigt_post.couette (no voigt run; numpy, scipy for the
smoothed Couette state). Standard library unittest; CTest runs it with python.voigt_post."""
import math
import unittest

from voigt_post import formulas
from voigt_post.formulas import heaviside

try:
    import numpy as np
except ImportError:  # scripts/setup --figures installs python3-numpy
    np = None
try:
    import scipy  # noqa: F401
except ImportError:
    scipy = None

# Rounding: sin(pi) is 1.2e-16 in doubles, so H(+-kappa) from the formula's middle branch would
# be off by ~2e-17; sums of a few thousand terms of size 1 carry ~1e-13.
ULP = 1e-15


class HeavisideTest(unittest.TestCase):
    def test_known_points(self):
        for kappa in (0.25, 1.0, 3e-3):
            self.assertEqual(heaviside(0.0, kappa), 0.5)                         # the interface
            self.assertAlmostEqual(heaviside(kappa, kappa), 1.0, delta=ULP)      # band edges
            self.assertAlmostEqual(heaviside(-kappa, kappa), 0.0, delta=ULP)
            self.assertEqual(heaviside(1.0001 * kappa, kappa), 1.0)              # beyond: exact
            self.assertEqual(heaviside(-1.0001 * kappa, kappa), 0.0)
            self.assertEqual(heaviside(-50 * kappa, kappa), 0.0)
            # half-way into the band: (1 + 1/2 + 1/pi) / 2 = 0.909..., Eq. (4) by hand
            self.assertAlmostEqual(heaviside(0.5 * kappa, kappa), 0.75 + 0.5 / math.pi, delta=ULP)

    def test_symmetric_and_monotone(self):
        kappa = 0.3
        xs = [kappa * (i / 50.0 - 1.5) for i in range(151)]
        hs = [heaviside(x, kappa) for x in xs]
        for x, h in zip(xs, hs):
            self.assertAlmostEqual(h + heaviside(-x, kappa), 1.0, delta=ULP)    # H(s) + H(-s) = 1
        self.assertTrue(all(b >= a - ULP for a, b in zip(hs, hs[1:])))     # H(kappa-) may round past 1

    def test_slope_at_the_interface(self):
        # dH/dpsi at 0 = (1/kappa + 1/kappa) / 2 = 1/kappa; central difference, error O(d^2)
        kappa, d = 0.2, 1e-5
        slope = (heaviside(d, kappa) - heaviside(-d, kappa)) / (2 * d)
        self.assertAlmostEqual(slope, 1 / kappa, delta=1e-6)

    @unittest.skipIf(np is None, "needs numpy")
    def test_arrays_agree_with_scalars(self):
        kappa = 0.125
        psi = np.linspace(-0.2, 0.2, 81).reshape(9, 9)
        h = heaviside(psi, kappa)
        self.assertEqual(h.shape, psi.shape)
        for p, v in zip(psi.ravel(), h.ravel()):
            self.assertAlmostEqual(v, heaviside(float(p), kappa), delta=ULP)    # np.sin vs math.sin
        self.assertEqual(heaviside([0.0, 1.0], kappa).tolist(), [0.5, 1.0])     # a list: an array

    @unittest.skipIf(np is None, "needs numpy")
    def test_integrals(self):
        kappa = 0.1
        # int_{-L}^{L} H = L for any L >= kappa (H - 1/2 is odd); trapezoid rule on 200001 points
        s = np.linspace(-0.3, 0.3, 200001)
        self.assertAlmostEqual(np.trapz(heaviside(s, kappa), s), 0.3, delta=1e-10)
        # Volume of a sphere of radius r smoothed by H over its signed distance:
        # 4 pi int (r - s)^2 H(s) ds = 4/3 pi r^3 + 8 pi r kappa^2 (1/6 - 1/pi^2): H - step is odd,
        # so of (r - s)^2 only -2 r s adds, -16 pi r int_0^kappa s (H - 1) ds, and
        # int_0^kappa s (H - 1) ds = kappa^2 (1/(2 pi^2) - 1/12).
        r = 0.5
        s = np.linspace(-kappa, r, 400001)
        vol = np.trapz(4 * math.pi * (r - s) ** 2 * heaviside(s, kappa), s)
        exact = 4 / 3 * math.pi * r ** 3 + 8 * math.pi * r * kappa ** 2 * (1 / 6 - 1 / math.pi ** 2)
        self.assertAlmostEqual(vol, exact, delta=1e-9)                           # trapezoid error ~ ds^2


@unittest.skipIf(np is None, "needs numpy")
class TaylorGreenTest(unittest.TestCase):
    def grid(self, n):
        x = np.arange(n) * 2 * math.pi / n
        return x, x

    def test_exact_field_has_no_error(self):
        x, y = self.grid(16)
        t = 0.7
        vx, vy = formulas.taylor_green_velocity(x, y, t)
        u = np.zeros((4, 16, 16, 3))
        u[..., 0], u[..., 1] = vx, vy
        self.assertEqual(formulas.taylor_green_rms(u, x, y, t), (0.0, 0.0))
        # decay e^{-2 nu t}: the largest u_x is the amplitude, reached at x = pi/2, y = 0
        self.assertAlmostEqual(vx.max(), math.exp(-2 * formulas.TG_NU * t), delta=ULP)

    def test_offset_gives_its_size(self):
        x, y = self.grid(8)
        vx, vy = formulas.taylor_green_velocity(x, y, 1.0)
        u = np.zeros((2, 8, 8, 3))
        u[..., 0], u[..., 1], u[..., 2] = vx, vy, 1e-3      # u_z = 1e-3 everywhere, exact u_z = 0
        rms, mx = formulas.taylor_green_rms(u, x, y, 1.0)
        self.assertAlmostEqual(rms, 1e-3, delta=1e-17)   # sum of e^2 over the 3 components / nodes: u_z only
        self.assertAlmostEqual(mx, 1e-3, delta=1e-18)


@unittest.skipIf(np is None, "needs numpy")
class CouetteTest(unittest.TestCase):
    def setUp(self):
        from voigt_post import couette
        self.m = couette
        self.c = couette.Couette(**couette.case_params())

    def test_parameters_from_the_scene(self):
        # elastic_couette.yaml's numbers, those of tests/elasticity/test_couette.cpp.
        self.assertEqual(self.m.case_params(), dict(rho_s=1000.0, G=100.0, eta_s=0.0, rho_f=1000.0, mu=0.3, a=0.005,
                                                    b=0.01, V=1e-4, omega=90.0))

    def test_boundary_and_interface_conditions(self):
        c = self.c
        self.assertLess(abs(c.U(0.0)), 1e-20)                     # bonded to the fixed wall
        self.assertLess(abs(c.U(c.b) - c.V) / c.V, 1e-12)         # the moving wall's amplitude
        jump = c.A * np.sin(c.ks * c.a) - c.B                      # velocity continuous at y = a
        self.assertLess(abs(jump) / c.V, 1e-12)
        ts = c.Gc * c.A * c.ks * np.cos(c.ks * c.a) / (1j * c.omega)   # shear stress continuous
        tf = c.mu * c.kf * c.C
        self.assertLess(abs(ts - tf) / abs(tf), 1e-12)

    @unittest.skipIf(scipy is None, "needs scipy")
    def test_smoothed_state_tends_to_the_sharp_one(self):
        c, errs = self.c, []
        for cells in (12, 48):
            y, U = self.m.smoothed(c, c.b / cells, n=4000)
            self.assertAlmostEqual(abs(U[0]), 0.0, delta=1e-20)
            self.assertEqual(U[-1], c.V)
            errs.append(np.sqrt(np.mean(np.abs(U - c.U(y)) ** 2)) / c.V)
        # kappa = 2 h: the error falls as the band narrows (first order in kappa at best;
        # couette.py --smoothing: 6.7e-3 at 12 cells)
        self.assertLess(errs[1], errs[0])
        self.assertLess(errs[0], 0.05)


if __name__ == "__main__":
    unittest.main()
