#!/usr/bin/python3
"""Thumbnails for cases/README.md of the three cases with exact solutions and no picture of their
own: runs each scene with build/voigt (a few seconds each) into a directory outside the tree and
draws the numerical result against the exact solution (matplotlib, Agg) into the case's folder:

    channel/thumbnail.png       Couette start-up and Poiseuille profiles u_x(y) against the exact ones
    shear_wave/thumbnail.png    kinetic energy of shear_wave_tg.yaml against cos^2(c |k| t)
    taylor_green/thumbnail.png  |u| in the mid z-plane at t = 1, RMS error against the exact vortex

    /usr/bin/python3 cases/thumbnails.py [-o /tmp/voigt-thumbnails] [--voigt build/voigt] [--only CASE ...]
        [--figures DIR]

The exact solutions take their parameters (viscosity, wall speed, driving acceleration,
amplitude, shear modulus, the box) from each run's scene record (scene.yaml). --figures DIR
writes DIR/<case>_thumbnail.png instead of the cases' own thumbnail.png (the tests do).
"""
import argparse
import os
import subprocess
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from voigt_post import fields, launch, scene_record, series  # noqa: E402
from voigt_post.formulas import taylor_green_rms  # noqa: E402
from voigt_post.xdmf import frames  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = launch.REPO

plt.rcParams.update({"font.size": 7, "axes.titlesize": 7, "legend.fontsize": 6})


def run(args, scene, name, *sets):
    """Runs cases/SCENE (--set SETS) into OUT/NAME and returns the output directory (its scene
    record: scene_record.scene(it))."""
    out = os.path.join(args.out, name)
    t0 = time.time()
    subprocess.run(launch.voigt_cmd(args.voigt, os.path.join(HERE, scene), out, sets),
                   check=True, stdout=subprocess.DEVNULL)
    print("%-14s %5.1f s  %s" % (name, time.time() - t0, out))
    return out


def velocity(frame):
    """Node velocity (z, y, x, 3; periodic duplicate nodes included) and the nodes' y."""
    u = fields.read(frame.path, "velocity")
    y = frame.origin[1] + frame.spacing[1] * np.arange(u.shape[1])
    return u, y


def save(fig, case, figures=None):
    path = os.path.join(figures, case + "_thumbnail.png") if figures else os.path.join(HERE, case, "thumbnail.png")
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print("%-14s wrote %s (%d bytes)" % ("", os.path.relpath(path, ROOT), os.path.getsize(path)))


def viscosity(sc):
    """Kinematic viscosity nu = mu / rho of the scene's fluid."""
    m = scene_record.material(sc, sc.get("fluid") or next(iter(sc["materials"])))
    return float(m["viscosity"]) / float(m["density"])


def couette_exact(y, t, nu, U=1.0, L=1.0, terms=400):
    """Start-up Couette flow between walls L apart, the upper one at U (cases/channel/README.md)."""
    n = np.arange(1, terms + 1)[:, None]
    return U * (y / L - (2 / np.pi) * np.sum((-1.0) ** (n + 1) / n * np.sin(n * np.pi * y / L)
                                             * np.exp(-nu * (n * np.pi / L) ** 2 * t), 0))


def poiseuille_exact(y, t, g, nu, L=1.0, terms=401):
    """Poiseuille flow from rest between walls L apart: g y (L - y) / 2 nu less its sine modes
    (odd n) decaying as exp(-nu n^2 pi^2 t / L^2)."""
    n = np.arange(1, terms + 1, 2)[:, None]
    return g / (2 * nu) * np.sum(8 * L ** 2 / (n * np.pi) ** 3 * np.sin(n * np.pi * y / L)
                                 * (1 - np.exp(-nu * (n * np.pi / L) ** 2 * t)), 0)


def channel(args):
    cou_out = run(args, "channel/couette.yaml", "couette")
    poi_out = run(args, "channel/poiseuille.yaml", "poiseuille", "output.interval=0.5")
    cou, poi = frames(cou_out), frames(poi_out)
    sc, sp = scene_record.require(cou_out, "thumbnails.py"), scene_record.require(poi_out, "thumbnails.py")
    (_, lo, _), (_, hi, _) = scene_record.extent(sc)
    L, U, nu = hi - lo, float(sc["boundaries"]["y+"]["velocity"][0]), viscosity(sc)   # gap, wall speed
    g, nu_p = float(sp["gravity"][0]), viscosity(sp)                                 # driving acceleration
    fig, (a, b) = plt.subplots(1, 2, figsize=(4, 3), sharey=True)
    yy = np.linspace(0, L, 201)
    for f, c in zip([cou[1], cou[2], cou[-1]], ["C0", "C1", "C2"]):
        u, y = velocity(f)
        a.plot(couette_exact(yy, f.t, nu, U, L), yy, "-", c=c, lw=0.8)
        a.plot(u[0, :, 0, 0], y, "o", c=c, ms=2, label="t = %.1f" % f.t)
        err = u[:-1, :, :-1, :].copy()
        err[..., 0] -= couette_exact(y, f.t, nu, U, L)[None, :, None]
    rms = np.sqrt(np.mean(np.sum(err ** 2, -1)))
    a.set_title("start-up Couette, %d cells\nRMS error %.1e at t = %g" % (sc["domain"]["cells"][1], rms, cou[-1].t))
    a.set_xlabel("u_x")
    a.set_ylabel("y")
    a.legend(loc="lower right", title="o Voigt, - exact series", title_fontsize=6)
    for f, c in zip([poi[1], poi[3], poi[-1]], ["C0", "C1", "k"]):
        u, y = velocity(f)
        b.plot(poiseuille_exact(yy, f.t, g, nu_p, L), yy, "-", c=c, lw=0.8)
        b.plot(u[0, :, 0, 0], y, "o", c=c, ms=2, label="t = %g" % f.t)
    dev = np.max(np.abs(u[..., 0] - (g * y * (L - y) / (2 * nu_p))[None, :, None]))
    b.set_title("Poiseuille from rest, %d cells\nmax |u - exact| %.0e at t = %g" % (sp["domain"]["cells"][1], dev,
                                                                                 poi[-1].t))
    b.set_xlabel("u_x")
    b.set_xlim(-0.04, 1.5)
    b.legend(loc="lower right", title="- exact: g y(1-y)/2nu\n  less decaying modes", title_fontsize=6)
    fig.tight_layout()
    save(fig, "channel", args.figures)


def shear_wave(args):
    out = run(args, "shear_wave/shear_wave_tg.yaml", "shear_wave_tg")
    sc = scene_record.require(out, "thumbnails.py")
    d = series.timeseries(out)
    t, ke = np.array(d["t"]), np.array(d["kinetic_energy"])
    (x0, y0, z0), (x1, y1, z1) = scene_record.extent(sc)
    solid = scene_record.material(sc, scene_record.level_set(sc)["phase"])
    rho, amp = float(solid["density"]), float(sc["initial"]["amplitude"])
    # rho U^2 <sin^2 cos^2 + cos^2 sin^2> / 2 x volume, U the amplitude
    ke0 = 0.5 * rho * amp ** 2 / 2 * ((x1 - x0) * (y1 - y0) * (z1 - z0))
    # c |k|: the shear wave's speed sqrt(mu_S / rho) and the vortex's wave number 2 pi |(1/Lx, 1/Ly)|
    omega = np.sqrt(float(solid["shear_modulus"]) / rho) * (2 * np.hypot(1 / (x1 - x0), 1 / (y1 - y0)) * np.pi)
    mins = []  # kinetic-energy minima, parabolic interpolation (as in the README)
    for i in range(1, len(t) - 1):
        if ke[i] < ke[i - 1] and ke[i] <= ke[i + 1]:
            p, q, r = ke[i - 1:i + 2]
            mins.append(t[i] + 0.5 * (t[i] - t[i - 1]) * (p - r) / (p - 2 * q + r))
    om = np.pi / np.mean(np.diff(mins))
    fig, a = plt.subplots(figsize=(4, 3))
    tt = np.linspace(0, t[-1], 600)
    a.plot(tt, np.cos(omega * tt) ** 2, "k-", lw=0.8, label="exact cos^2(c|k| t), c|k| = %.4f" % omega)
    a.plot(t, ke / ke0, "o", c="C0", ms=2, label="Voigt, every step (dt = h/2c)")
    dt = t[1] - t[0]
    a.plot(tt, np.cos(om * (tt - dt / 2)) ** 2, "--", c="C0", lw=0.6,
           label="cos^2(omega (t - dt/2)): tau_S = 0 is at dt/2 (staggered)")
    a.plot(mins, np.zeros(len(mins)), "|", c="C3", ms=8, label="minima: omega = %.4f (%+.1e)" % (om, om / omega - 1))
    a.set_xlabel("t")
    a.set_ylabel("kinetic energy / initial")
    a.set_ylim(-0.05, 1.3)
    a.set_title("shear waves in an elastic box (shear_wave_tg.yaml, %d x %d)\n"
                "u(0) Taylor-Green, U = %s: u(t) = u(0) cos(c |k| t), |k| = 2 sqrt(2) pi"
                % (sc["domain"]["cells"][0], sc["domain"]["cells"][1], ("%.0e" % amp).replace("e-0", "e-")))
    a.legend(loc="upper center", ncol=1)
    fig.tight_layout()
    save(fig, "shear_wave", args.figures)


def taylor_green(args):
    out = run(args, "taylor_green/taylor_green.yaml", "taylor_green")
    sc = scene_record.require(out, "thumbnails.py")
    nu, amp0 = viscosity(sc), float(sc["initial"]["amplitude"])
    f = frames(out)[-1]
    u = fields.read(f.path, "velocity")
    nz, ny, nx, _ = u.shape
    x = f.origin[0] + f.spacing[0] * np.arange(nx)
    y = f.origin[1] + f.spacing[1] * np.arange(ny)
    X, Y = np.meshgrid(x, y)
    amp = amp0 * np.exp(-2 * nu * f.t)
    rms, _ = taylor_green_rms(u[:-1, :-1, :-1, :], x[:-1], y[:-1], f.t, nu, amp0)  # as tests/flow/test_taylor_green.cpp
    mid = u[nz // 2]
    fig, a = plt.subplots(figsize=(4, 3))
    im = a.imshow(np.hypot(mid[..., 0], mid[..., 1]), origin="lower", extent=[x[0], x[-1], y[0], y[-1]],
                  cmap="viridis", interpolation="nearest")
    s = slice(0, None, 3)
    a.quiver(X[s, s], Y[s, s], mid[s, s, 0], mid[s, s, 1], color="w", scale=10, width=0.006)
    fig.colorbar(im, ax=a, label="|u|", shrink=0.9)
    a.set_xlabel("x")
    a.set_ylabel("y")
    a.set_title("Taylor-Green, %d x %d x %d, Re = %g: |u| at t = %g, mid z-plane\n"
                "RMS error vs exact A e^{-2 nu t} (sin x cos y, -cos x sin y): %.2e (%.2f %%)"
                % (tuple(sc["domain"]["cells"]) + (amp0 / nu, f.t, rms, 100 * rms / amp)))
    fig.tight_layout()
    save(fig, "taylor_green", args.figures)


CASES = {"channel": channel, "shear_wave": shear_wave, "taylor_green": taylor_green}

if __name__ == "__main__":
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("-o", "--out", default="/tmp/voigt-thumbnails", help="run directory (default %(default)s)")
    p.add_argument("--voigt", default=os.path.join(ROOT, "build", "voigt"))
    p.add_argument("--only", nargs="+", choices=sorted(CASES), default=sorted(CASES))
    p.add_argument("--figures", help="write DIR/<case>_thumbnail.png here, not into the cases' folders")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.figures:
        os.makedirs(args.figures, exist_ok=True)
    t0 = time.time()
    for name in args.only:
        CASES[name](args)
    print("all done in %.1f s" % (time.time() - t0))
