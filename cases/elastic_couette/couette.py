#!/usr/bin/python3
"""Oscillatory Couette flow over an elastic layer: analytic periodic state and plots.

Solid 0 < y < a (density rho_s, shear modulus G, optional Kelvin-Voigt viscosity eta_s)
bonded to the fixed wall y = 0; fluid a < y < b (density rho_f, viscosity mu); the wall
y = b moves as V sin(omega t). u(y, t) = Im[U(y) exp(i omega t)] with (README.md)
    solid  U = A sin(k_s y),                               k_s = omega sqrt(rho_s / (G + i omega eta_s))
    fluid  U = B cosh(k_f (y - a)) + C sinh(k_f (y - a)),  k_f = sqrt(i omega rho_f / mu)
    B = A sin(k_s a),  mu k_f C = (G + i omega eta_s) k_s cos(k_s a) A / (i omega),  U(b) = V.
The formulas live in python/voigt_post/couette.py (Couette, params, smoothed; perf/accuracy uses them
too); the same in C++ are in tests/elasticity/couette_exact.hpp (used by the test).

Usage:
  couette.py --check                 verify the formulas (ODE residual, interface jumps) numerically
  couette.py [--csv DIR] [-o PNG]    plot analytic profiles over one period; with --csv, also the
                                     numerical profiles the test writes when run with
                                     VOIGT_COUETTE_PROFILES=DIR (files profile_<cells>.csv:
                                     y, u_numerical, u_exact at the end time t, in the header),
                                     and the smoothed-interface model's profile (needs scipy)
  couette.py --probe FILE [-o PNG]   `voigt run` from rest: error per probe sample, last period plotted
  couette.py --smoothing 24 48 96    error of the smoothed-interface periodic state (kappa = 2 h,
                                     Eq. 4) against the sharp one: the error the test should see
The parameters: with --probe, the scene record of the run that wrote FILE (its folder); else,
or for a run without a record, the case's elastic_couette.yaml (the parameters of
tests/elasticity/test_couette.cpp too). --rho_s, --G, ... override them.
"""
import argparse
import glob
import os

import numpy as np

from voigt_post import scene_record, series
from voigt_post.couette import SCENE, Couette, case_params, params, smoothed


def check(c):
    """Finite-difference residuals of the governing equations and the interface conditions."""
    om = c.omega
    h = 1e-4 * c.b
    ok = True
    for y, rho, label in ((0.3 * c.a, c.rho_s, "solid"), (c.a + 0.4 * (c.b - c.a), c.rho_f, "fluid")):
        # i omega rho U = d/dy (complex stress amplitude): second difference of U.
        d2 = (c.U(y + h) - 2 * c.U(y) + c.U(y - h)) / h**2
        mod = c.Gc / (1j * om) if label == "solid" else c.mu
        r = abs(1j * om * rho * c.U(y) - mod * d2) / abs(1j * om * rho * c.U(y))
        print(f"{label} momentum residual (relative): {r:.2e}")
        ok &= r < 1e-4
    jumpU = abs(c.A * np.sin(c.ks * c.a) - c.B) / c.V
    ts = c.Gc * c.A * c.ks * np.cos(c.ks * c.a) / (1j * om)
    tf = c.mu * c.kf * c.C
    jumpT = abs(ts - tf) / abs(tf)
    wall = abs(c.U(c.b) - c.V) / c.V
    print(f"interface velocity jump {jumpU:.1e}, stress jump {jumpT:.1e}, U(b) - V {wall:.1e}, U(0) {abs(c.U(0.0)):.1e}")
    print(f"k_s a = {c.ks * c.a:.4f}, |k_f| (b - a) = {abs(c.kf) * (c.b - c.a):.4f}, "
          f"boundary layer sqrt(2 mu / (rho_f omega)) = {np.sqrt(2 * c.mu / (c.rho_f * om)):.4e}")
    print(f"max |u| in the solid / V = {np.max(np.abs(c.U(np.linspace(0, c.a, 201)))) / c.V:.4f}, "
          f"max strain = {np.max(np.abs(c.dU(np.linspace(0, c.b, 401)))) / om:.3e}")
    ok &= jumpU < 1e-12 and jumpT < 1e-12 and wall < 1e-12
    print("check:", "ok" if ok else "FAILED")
    return ok


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--smoothing", type=int, nargs="*", metavar="CELLS",
                    help="error of the smoothed-interface periodic state (kappa = 2 h) against the sharp one, "
                         "for these cell counts across the gap (needs scipy)")
    ap.add_argument("--csv", help="folder with profile_<cells>.csv written by the test")
    ap.add_argument("--probe", help="probe_profile.csv of `voigt run elastic_couette.yaml` (started from rest): "
                                    "error per sample, and the last period against the analytic state")
    ap.add_argument("-o", "--out", help="PNG (default: profiles.png beside this script with --csv, else analytic.png)")
    defaults = case_params()
    for k in defaults:
        ap.add_argument("--" + k, type=float, help="default: the scene's")
    args = ap.parse_args()
    if args.probe:   # the run's own parameters (its scene record, with every --set it ran)
        run = os.path.dirname(os.path.abspath(args.probe))
        defaults = params(scene_record.scene_or(run, SCENE, "couette.py"))
    c = Couette(**{k: v if getattr(args, k) is None else getattr(args, k) for k, v in defaults.items()})
    if args.out is None:
        args.out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "profiles.png" if args.csv else "analytic.png")
    if args.check:
        raise SystemExit(0 if check(c) else 1)
    if args.smoothing:
        prev = None
        for cells in args.smoothing:
            h = c.b / cells
            y, U = smoothed(c, h)
            nodes = np.arange(cells + 1) * h
            Us = np.interp(nodes, y, U.real) + 1j * np.interp(nodes, y, U.imag)
            d = Us - c.U(nodes)
            # RMS over a period of Im[d e^{i w t}] is |d| / sqrt(2); RMS over the nodes too.
            rms = np.sqrt(np.mean(np.abs(d) ** 2) / 2) / c.V
            mx = np.max(np.abs(d)) / c.V
            at_T = np.sqrt(np.mean(d.imag ** 2)) / c.V  # at t = whole periods (what the test measures)
            order = "" if prev is None else f", order {np.log2(prev / rms):.2f}"
            print(f"{cells} cells: smoothed vs sharp periodic state, RMS (nodes, period) / V = {rms:.3e}, "
                  f"max amplitude / V = {mx:.3e}{order}; at t = n T: RMS / V = {at_T:.3e}, "
                  f"max / V = {np.max(np.abs(d.imag)) / c.V:.3e}")
            prev = rms
        return

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if args.probe:
        raw = series.probe_array(args.probe)
        times = np.unique(raw["t"])
        period = 2 * np.pi / c.omega
        print("t / T, RMS error / V of u_x against the periodic state (start-up transient decaying):")
        for t in times:
            r = raw[raw["t"] == t]
            e = np.sqrt(np.mean((r["velocity_x"] - c.u(r["y"], t)) ** 2)) / c.V
            print(f"  {t / period:7.3f}  {e:.3e}")
        last = times[-8:]
        fig, ax = plt.subplots(figsize=(6, 4.5))
        yy = np.linspace(0, c.b, 401)
        for j, t in enumerate(last):
            r = raw[raw["t"] == t]
            col = plt.cm.viridis(j / len(last))
            ax.plot(c.u(yy, t) / c.V, yy * 1e3, "-", color=col, lw=1)
            ax.plot(r["velocity_x"] / c.V, r["y"] * 1e3, "o", ms=2.5, mfc="none", color=col,
                    label=f"t = {t / period:.3g} T")
        ax.axhspan(0, c.a * 1e3, color="0.9", zorder=0)
        ax.set_xlabel("u / V")
        ax.set_ylabel("y [mm]")
        ax.set_title("voigt run from rest: last period (lines: analytic)")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(args.out, dpi=120)
        print("wrote", args.out)
        return

    period = 2 * np.pi / c.omega
    y = np.linspace(0, c.b, 801)
    files = sorted(glob.glob(os.path.join(args.csv, "profile_*.csv")), key=lambda f: int(f.split("_")[-1][:-4])) \
        if args.csv else []
    fig, axes = plt.subplots(1, 2 if files else 1, figsize=(11 if files else 6, 4.5), squeeze=False)
    ax = axes[0][0]
    for j, ph in enumerate(np.arange(8) / 8):
        ax.plot(c.u(y, ph * period) / c.V, y * 1e3, color=plt.cm.viridis(j / 8), label=f"t = {ph:.3g} T")
    ax.axhspan(0, c.a * 1e3, color="0.9", zorder=0)
    ax.set_xlabel("u / V")
    ax.set_ylabel("y [mm]")
    ax.set_title("analytic periodic state (grey: solid)")
    ax.legend(fontsize=7)
    if files:
        ax = axes[0][1]
        markers = "os^d"
        for n, f in enumerate(files):
            with open(f) as fh:
                head = fh.readline()
            t = float(head.split("t=")[1].split()[0])
            d = np.loadtxt(f, delimiter=",", comments="#", skiprows=2)
            cells = f.split("_")[-1][:-4]
            line, = ax.plot(d[:, 1] / c.V, d[:, 0] * 1e3, markers[n % 4], ms=3, mfc="none",
                            label=f"Voigt, {cells} cells across")
            ys, Us = smoothed(c, c.b / int(cells))
            ax.plot(np.imag(Us * np.exp(1j * c.omega * t)) / c.V, ys * 1e3, "--", lw=0.8, color=line.get_color(),
                    label=f"smoothed-interface model, kappa = 2 h ({cells})")
            err = np.sqrt(np.mean((d[:, 1] - c.u(d[:, 0], t)) ** 2)) / c.V
            print(f"{cells} cells: t = {t:.6g}, RMS error / V = {err:.3e} (python exact)")
        ax.plot(c.u(y, t) / c.V, y * 1e3, "k-", lw=1, label="analytic (sharp interface)")
        ax.axhspan(0, c.a * 1e3, color="0.9", zorder=0)
        ax.set_xlabel("u / V")
        ax.set_title(f"t = {t / period:.3g} T, started from the exact state")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
