#!/usr/bin/python3
"""The stress wave of the impact: S2 along the probe line `impact` (x through the block's middle,
falling_block.yaml) against time, one panel per run, and the speed of its front against the
shear-wave speed c_s = sqrt(mu_S / rho_S) (summary.json). Python 3 + numpy + matplotlib.

    cases/falling_block/waves.py -o waves.png --run output/fb_5000 "mu_S = 5000 Pa" [--run ...]
        [--window 0.04 0.10] [--level 0.1] [--source X Y] [--title TEXT]

Impact time t_i: the block's mean vertical velocity (timeseries.csv, solid_vy) stops falling,
i.e. first rises 1 % of its size above its running minimum. Only samples more than a cell
inside the block count (psi > h: the band's air side carries stress from the air flow, README).
Arrival at x: the first time after t_i - 2 ms at which S2 there exceeds LEVEL times the largest
S2 on the line in the window. The source is the contact, the cylinder's top under the block
(--source X Y; default the top of the cylinder in the run's scene.yaml, or 4.5, 4.75 cm for runs without one); the front speed on each side is 1 / slope
of a Theil-Sen line (median pairwise slope) of arrival time against the distance r from the
source, over 2 h <= |x - x_0| <= 2.5 cm, printed only where that line explains the arrivals
(R^2 >= 0.8). Caveats: the load builds up for ~15 ms after t_i while a shear wave crosses
2.5 cm in 3.5-8 ms, so the arrival mixes propagation with how fast S2 grows at each x; and
the line is fixed while the block moves (its centre is at the line's height, 5.9 cm, on
impact at 75^3 and sinks ~3 mm after; at 30^3 it is 3-5 mm higher).
Prints a markdown table (speeds, their ratio to c_s, the fit's R^2).
"""
import argparse

import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from events import slowing  # noqa: E402  (the same impact rule as plots.py's events table)
from voigt_post import digest, series  # noqa: E402
from voigt_post.scene_record import cylinder  # noqa: E402
from voigt_post.xdmf import frames  # noqa: E402


def probe(d):
    """t (nt), x (nx), the line's height y, psi and S2 (nt, nx) from DIR/probe_impact.csv."""
    samples = series.probe(d, "impact")
    ts = sorted(samples)
    if not ts:
        return None
    rows = {t: [(r["x"], r["psi"], r["S2"]) for r in samples[t]] for t in ts}
    y = samples[ts[-1]][-1]["y"]
    x = np.array([p[0] for p in rows[ts[0]]])
    psi = np.array([[p[1] for p in rows[t]] for t in ts])
    s2 = np.array([[p[2] for p in rows[t]] for t in ts])
    return np.array(ts), x, y, psi, s2


def impact_time(d):
    cols = series.timeseries(d)
    hit = slowing(cols["t"], cols["solid_vy"])
    return hit[0] if hit else None


def front(t, x, y, psi, s2, t0, t1, level, h, src):
    """Arrival time per x (nan where none) and the fit on each side."""
    win = (t >= t0) & (t <= t1)
    inside = np.where(psi > h, s2, np.nan)[win]
    tw = t[win]
    arrive = np.full(len(x), np.nan)
    if np.all(np.isnan(inside)):
        return arrive, []
    peak = np.nanmax(inside)
    for q in range(len(x)):
        hit = np.where(inside[:, q] >= level * peak)[0]
        if len(hit):
            arrive[q] = tw[hit[0]]
    if np.all(np.isnan(arrive)):
        return arrive, []
    fits = []
    x0 = src[0]
    dist = np.hypot(x - x0, y - src[1])
    for side, sel in (("-x", x < x0), ("+x", x > x0)):
        m = sel & ~np.isnan(arrive) & (np.abs(x - x0) >= 2 * h) & (np.abs(x - x0) <= 0.025)
        if m.sum() < 4:
            fits.append((side, None, None, int(m.sum())))
            continue
        # Theil-Sen (median of the pairwise slopes): a few late arrivals, where S2 grows
        # slowly over the cylinder's line, do not pull it; R^2 of that line for how well it fits.
        dd, tt = dist[m], arrive[m]
        i, j = np.triu_indices(len(dd), 1)
        ok = dd[j] != dd[i]
        slope = np.median((tt[j] - tt[i])[ok] / (dd[j] - dd[i])[ok])
        icpt = np.median(tt - slope * dd)
        r2 = 1 - np.sum((tt - slope * dd - icpt) ** 2) / max(np.sum((tt - tt.mean()) ** 2), 1e-300)
        fits.append((side, 1 / slope if slope > 0 and r2 >= 0.8 else None, r2, int(m.sum())))
    return arrive, fits


def wave_speed(d, given):
    """c_s from DIR/summary.json; a run still going has none yet, so --wave-speed stands in."""
    try:
        return series.summary(d)["elasticity"]["wave_speed"]
    except FileNotFoundError:
        if given is None:
            raise SystemExit("waves.py: %s has no summary.json (still running?): pass --wave-speed "
                             "sqrt(mu_S / rho_S)" % d)
        return given


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", nargs=2, action="append", metavar=("DIR", "LABEL"), required=True)
    ap.add_argument("--window", nargs=2, type=float, default=(0.04, 0.10), metavar=("T0", "T1"))
    ap.add_argument("--level", type=float, default=0.1)
    ap.add_argument("--source", nargs=2, type=float, default=None, metavar=("X", "Y"),
                    help="the contact (m); default: the top of each run's cylinder (scene_record.py)")
    ap.add_argument("--wave-speed", type=float, metavar="C_S",
                    help="c_s (m/s) for every run without summary.json yet (still running); the others use their own")
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    missing = [d for d, _ in a.run if not series.has(d, "probe_impact.csv")]
    for d in missing:
        print("waves.py: %s has no probe_impact.csv (run before the probe was in the scene): skipped" % d)
    a.run = [r for r in a.run if r[0] not in missing]
    if not a.run:
        return
    fig, axes = plt.subplots(1, len(a.run), figsize=(4.2 * len(a.run) + 1, 4.6), squeeze=False)
    speeds = [wave_speed(d, a.wave_speed) for d, _ in a.run]
    print("| run | impact t_i (s) | source x_0 (cm) | side | front speed (m/s) | c_s (m/s) | speed / c_s | R^2 | points |")
    print("|---|---|---|---|---|---|---|---|---|")
    for ax, (d, label), cs in zip(axes[0], a.run, speeds):
        got = probe(d)
        win = got is not None and (got[0] >= a.window[0]) & (got[0] <= a.window[1])
        if got is None or not win.any():
            print("| %s | - | - | - | - | %.2f | - | - | 0 |" % (label, cs))
            ax.set_title(label + ": no samples in the window", fontsize=10)
            continue
        t, x, y, psi, s2 = got
        if a.source:
            src = a.source
        else:
            cx, cy, cr = cylinder(d)
            src = (cx, cy + cr)
        h = (digest.frames(d) if digest.is_digest(d) else frames(d))[0].spacing[0]
        ti = impact_time(d)
        t0 = max(a.window[0], (ti - 0.002) if ti else a.window[0])
        arrive, fits = front(t, x, y, psi, s2, t0, a.window[1], a.level, h, src)
        img = np.where(psi[win] > h, np.log10(np.maximum(s2[win], 1e-3)), np.nan)
        m = ax.pcolormesh(x * 100, t[win] * 1000, img, shading="nearest", cmap="viridis")
        fig.colorbar(m, ax=ax, label="log10 S2 (Pa^2), more than a cell inside")
        ax.plot(x * 100, arrive * 1000, "w.", ms=3, label="arrival (S2 > %g of its peak)" % a.level)
        if not np.all(np.isnan(arrive)):
            tx0 = np.nanmin(arrive) - np.hypot(0, y - src[1]) / cs
            dx = np.linspace(0, 0.03, 31)
            for sgn in (-1, 1):
                ax.plot((src[0] + sgn * dx) * 100, (tx0 + np.hypot(dx, y - src[1]) / cs) * 1000, "r--", lw=1)
            ax.plot([], [], "r--", lw=1, label="c_s = %.2f m/s from the contact" % cs)
        if ti:
            ax.axhline(ti * 1000, color="w", lw=0.8, ls=":")
        ax.set_xlabel("x (cm), at y = %.1f cm" % (y * 100))
        ax.set_ylabel("t (ms)")
        ax.set_title(label, fontsize=10)
        ax.legend(fontsize=7, loc="upper left")
        if not fits:
            fits = [("-", None, None, 0)]
        for side, v, r2, npts in fits:
            print("| %s | %s | %s | %s | %s | %.2f | %s | %s | %d |" % (
                label, "%.4f" % ti if ti else "-", "%.2f" % (src[0] * 100), side,
                "%.2f" % v if v else "-", cs, "%.2f" % (v / cs) if v else "-", "%.3f" % r2 if r2 is not None else "-",
                npts))
    if a.title:
        fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.output, dpi=130)
    print("\nwrote %s" % a.output)


if __name__ == "__main__":
    main()
