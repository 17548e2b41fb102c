"""Formulas the case scripts and perf studies share (numpy for arrays; scalars need only math).

- heaviside: the smoothed Heaviside of Eq. (4) of the paper, as kernels/heaviside.hpp;
- taylor_green_velocity, taylor_green_rms: the decaying Taylor-Green vortex of
  cases/taylor_green (as tests/flow/test_taylor_green.cpp) and a run's RMS error against it.
"""
import math


def heaviside(psi, kappa):
    """H(psi) of Eq. (4): 0 for psi < -kappa, 1 for psi > kappa, and in between
    (1 + psi / kappa + sin(pi psi / kappa) / pi) / 2. A Python float gives a float (math
    only); anything else (an array, a list, a numpy scalar) a numpy array of its shape."""
    if type(psi) in (int, float):
        if psi < -kappa:
            return 0.0
        if psi > kappa:
            return 1.0
        return 0.5 * (1 + psi / kappa + math.sin(math.pi * psi / kappa) / math.pi)
    import numpy as np
    psi = np.asarray(psi, dtype=float)
    inner = 0.5 * (1 + psi / kappa + np.sin(np.pi * psi / kappa) / np.pi)
    return np.where(psi < -kappa, 0.0, np.where(psi > kappa, 1.0, inner))


TG_NU, TG_AMP = 0.05, 1.0   # cases/taylor_green/taylor_green.yaml: viscosity (rho = 1), amplitude


def taylor_green_velocity(x, y, t, nu=TG_NU, amp=TG_AMP):
    """(u_x, u_y) on the grid of node coordinates x (ni) and y (nj), each of shape (nj, ni):
    amp e^{-2 nu t} (sin x cos y, -cos x sin y); u_z = 0."""
    import numpy as np
    X, Y = np.meshgrid(x, y)  # (j, i)
    dec = amp * math.exp(-2 * nu * t)
    return dec * np.sin(X) * np.cos(Y), -dec * np.cos(X) * np.sin(Y)


def taylor_green_rms(u, x, y, t, nu=TG_NU, amp=TG_AMP):
    """RMS over the nodes of u - exact, all three components, and the largest |u - exact|.
    u: the node velocity (k, j, i, 3) without periodic duplicates; x, y: its node coordinates
    (as tests/flow/test_taylor_green.cpp)."""
    import numpy as np
    nk, nj, ni = u.shape[:3]
    ex = np.zeros_like(u)
    vx, vy = taylor_green_velocity(x, y, t, nu, amp)
    ex[..., 0] = vx[None]
    ex[..., 1] = vy[None]
    e = u - ex
    return float(np.sqrt((e ** 2).sum() / (nk * nj * ni))), float(np.abs(e).max())
