"""Oscillatory Couette flow over an elastic layer (cases/elastic_couette): the exact periodic
state and the smoothed-interface model of it (numpy; scipy for `smoothed`).

Solid 0 < y < a (density rho_s, shear modulus G, optional Kelvin-Voigt viscosity eta_s)
bonded to the fixed wall y = 0; fluid a < y < b (density rho_f, viscosity mu); the wall
y = b moves as V sin(omega t). u(y, t) = Im[U(y) exp(i omega t)] with
    solid  U = A sin(k_s y),                               k_s = omega sqrt(rho_s / (G + i omega eta_s))
    fluid  U = B cosh(k_f (y - a)) + C sinh(k_f (y - a)),  k_f = sqrt(i omega rho_f / mu)
    B = A sin(k_s a),  mu k_f C = (G + i omega eta_s) k_s cos(k_s a) A / (i omega),  U(b) = V.
The same formulas are in tests/elasticity/couette_exact.hpp (C++, used by the test);
cases/elastic_couette/couette.py checks and plots them, perf/accuracy measures runs against them.
The parameters come from a scene (params: a run's record, or case_params: the case's file).
"""
import os

import numpy as np

from . import scene_record
from .formulas import heaviside
from .launch import REPO

SCENE = os.path.join(REPO, "cases", "elastic_couette", "elastic_couette.yaml")


def params(scene):
    """The keyword arguments of Couette for an elastic Couette scene (a dict): the solid of its
    level set (density, shear modulus, Kelvin-Voigt viscosity, 0 when it has none) below the
    plane y = a, the fluid above it, the gap b (the domain's height; y measured from its base)
    and the wall y+ moving as V sin(omega t)."""
    ls = scene_record.level_set(scene)
    solid, fluid = scene_record.material(scene, ls["phase"]), scene_record.material(scene)
    lo, hi = scene_record.extent(scene)
    wall = scene["boundaries"]["y+"]
    return dict(rho_s=float(solid["density"]), G=float(solid["shear_modulus"]),
                eta_s=float(solid.get("viscosity", 0.0)), rho_f=float(fluid["density"]),
                mu=float(fluid["viscosity"]), a=float(ls["shape"]["point"][1]) - lo[1], b=hi[1] - lo[1],
                V=float(wall["velocity"][0]), omega=float(wall["oscillation"]["omega"]))


def case_params():
    """params() of the case's scene file (cases/elastic_couette/elastic_couette.yaml; the
    parameters of tests/elasticity/test_couette.cpp too)."""
    return params(scene_record.load(SCENE))


class Couette:
    def __init__(self, rho_s, G, eta_s, rho_f, mu, a, b, V, omega):
        self.__dict__.update(locals())
        Gc = G + 1j * omega * eta_s
        self.Gc = Gc
        self.ks = omega * np.sqrt(rho_s / Gc + 0j)
        self.kf = np.sqrt(1j * omega * rho_f / mu)
        c_ratio = Gc * self.ks * np.cos(self.ks * a) / (1j * omega * mu * self.kf)
        b_ratio = np.sin(self.ks * a)
        L = b - a
        self.A = V / (b_ratio * np.cosh(self.kf * L) + c_ratio * np.sinh(self.kf * L))
        self.B = b_ratio * self.A
        self.C = c_ratio * self.A

    def U(self, y):
        y = np.asarray(y, dtype=float)
        s = self.A * np.sin(self.ks * y)
        f = self.B * np.cosh(self.kf * (y - self.a)) + self.C * np.sinh(self.kf * (y - self.a))
        return np.where(y <= self.a, s, f)

    def dU(self, y):
        y = np.asarray(y, dtype=float)
        s = self.A * self.ks * np.cos(self.ks * y)
        f = self.kf * (self.B * np.sinh(self.kf * (y - self.a)) + self.C * np.cosh(self.kf * (y - self.a)))
        return np.where(y <= self.a, s, f)

    def u(self, y, t):
        return np.imag(self.U(y) * np.exp(1j * self.omega * t))

    def stress(self, y, t):  # total shear stress tau_xy
        y = np.asarray(y, dtype=float)
        amp = np.where(y <= self.a, self.Gc * self.dU(y) / (1j * self.omega), self.mu * self.dU(y))
        return np.imag(amp * np.exp(1j * self.omega * t))


def smoothed(c, h, kappa_cells=2.0, n=20000):
    """Periodic state with the interface smoothed as in Voigt (Eq. 4, kappa = kappa_cells h):
    i omega rho(y) U = (M(y) U')',  M = H G*/(i omega) + (1 - H) mu,  rho = H rho_s + (1 - H) rho_f,
    H = H(a - y); U(0) = 0, U(b) = V. Second-order finite differences on n intervals (fine)."""
    kappa = kappa_cells * h
    y = np.linspace(0, c.b, n + 1)
    dy = y[1] - y[0]
    ym = 0.5 * (y[1:] + y[:-1])
    Hm = heaviside(c.a - ym, kappa)
    M = Hm * c.Gc / (1j * c.omega) + (1 - Hm) * c.mu
    H = heaviside(c.a - y, kappa)
    rho = H * c.rho_s + (1 - H) * c.rho_f
    from scipy.sparse import diags
    from scipy.sparse.linalg import spsolve
    main = -(M[1:] + M[:-1]) / dy**2 - 1j * c.omega * rho[1:-1]
    A = diags([M[1:-1] / dy**2, main, M[1:-1] / dy**2], [-1, 0, 1], format="csc")
    rhs = np.zeros(n - 1, dtype=complex)
    rhs[-1] -= M[-1] / dy**2 * c.V
    U = np.concatenate([[0], spsolve(A, rhs), [c.V]])
    return y, U
