#!/usr/bin/python3
"""Block diagnostics against time, one line per run (mu_S), from the solver's `solid_body` effect
(timeseries.csv every step, contact times in summary.json): centroid height, tilt of the thin
axis, bending of the mid-surface, and the gaps to the cylinder and the base; contact starts
(gap < contact_gap) marked. Python 3 + matplotlib.

    cases/falling_block/plots.py -o diagnostics.png --run output/fb_1000 "mu_S = 1000 Pa" \\
        --run output/fb_5000 "mu_S = 5000 Pa" [--title TEXT] [--csv results.csv] [--digests DIR]

A run is its output folder or its digest (<run id>.npz, voigt_post/digest.py; --digests writes
them for finished runs, and the study commits them in cases/falling_block/digests/).

Also prints three markdown tables: the contact times with tilt and bending at the paper's times,
the block's state at STATE_TIMES (centroid, tilt, bending, gaps in cells, energy ratio, volume
change), and the impact and what follows by one rule for every run (events()). Energy ratio = (kinetic energy of block and air + elastic energy) / potential
energy the block has released since t = 0; without an energy source it stays <= 1.
"""
import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", "..", "python"))  # voigt_post
from voigt_post import digest, series  # noqa: E402
from voigt_post.xdmf import frames  # noqa: E402

PAPER_TIMES = (0.04, 0.08, 0.12, 0.24, 0.36, 0.5)
DIGEST_PROBES = {"impact": (0.035, 0.11)}   # waves.py's window (0.04-0.10 s), not the probes of block_track.py
STATE_TIMES = (0.04, 0.06, 0.08, 0.10, 0.12, 0.16, 0.20, 0.24, 0.30, 0.36, 0.42, 0.50)
STATE_KEYS = ("solid_potential_energy", "kinetic_energy", "elastic_energy", "solid_cy", "solid_cx", "solid_tilt_deg",
              "solid_bending", "solid_gap_obstacle0", "solid_gap_y-", "volume_drift")


def load(d):
    cols = series.timeseries(d)
    summ = series.summary(d, None)
    if summ is None:  # a run still going: summary.json comes at the end
        print("plots.py: %s has no complete summary.json yet (still running?): no contact markers" % d)
        summ = {}
    return cols, summ


def at(cols, key, t):
    ts = cols["t"]
    if not ts or t > ts[-1] + 1e-9:
        return None
    i = min(range(len(ts)), key=lambda q: abs(ts[q] - t))
    return cols[key][i]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", nargs=2, action="append", metavar=("DIR", "LABEL"), required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--csv", help="also merge one row per finished run (results_row) into this CSV by run id")
    ap.add_argument("--digests", metavar="DIR", help="also write each finished run folder's digest to "
                    "DIR/<run id>.npz (voigt_post/digest.py: what this script, render.py and waves.py read)")
    a = ap.parse_args()
    fig, ax = plt.subplots(2, 2, figsize=(10, 7), sharex=True)
    ax = ax.ravel()
    rows, states, evs, h, results = [], [], [], None, []
    for n, (d, label) in enumerate(a.run):
        cols, summ = load(d)
        c = "C%d" % n
        t = cols["t"]
        sb = summ.get("solid_body", {})
        cont = sb.get("contacts", {})
        ax[0].plot(t, [1000 * v for v in cols["solid_cy"]], c, label=label)
        ax[1].plot(t, cols["solid_tilt_deg"], c, label=label)
        ax[2].plot(t, [1000 * v for v in cols["solid_bending"]], c, label=label)
        ax[3].plot(t, [1000 * v for v in cols["solid_gap_obstacle0"]], c, label=label + ": cylinder")
        ax[3].plot(t, [1000 * v for v in cols["solid_gap_y-"]], c + "--", label=label + ": base")
        for target, style in (("obstacle0", "v"), ("y-", "s")):
            for ts in cont.get(target, {}).get("contact_start_times", []):
                for k, key, scale in ((0, "solid_cy", 1000), (1, "solid_tilt_deg", 1), (2, "solid_bending", 1000)):
                    ax[k].plot([ts], [scale * at(cols, key, ts)], style, color=c, ms=7, mfc="none")
        first = {k: cont.get(k, {}).get("first_contact_time") for k in ("obstacle0", "y-")}
        starts = cont.get("obstacle0", {}).get("contact_start_times", [])
        rows.append((label, first["obstacle0"], starts[1] if len(starts) > 1 else None, first["y-"],
                     [at(cols, "solid_tilt_deg", tt) for tt in PAPER_TIMES],
                     [at(cols, "solid_bending", tt) for tt in PAPER_TIMES]))
        gap = sb.get("contact_gap")
        if gap:
            cell, h = gap / sb.get("contact_gap_cells", 1.0), gap
        else:  # a run still going: the grid's h
            cell = frames(d)[0].spacing[0] if not summ else None
        states.append((label, state_rows(cols, cell)))
        if cell:
            evs.append((label, events(cols, cell)))
        if series.finished(summ):
            results.append(results_row(d, cols, summ))
            if a.digests and not digest.is_digest(d):
                os.makedirs(a.digests, exist_ok=True)
                path = digest.write(d, os.path.join(a.digests, digest.run_id(d) + digest.SUFFIX), PAPER_TIMES,
                                    probes=DIGEST_PROBES)
                print("plots.py: digest %s (%.0f kB)" % (path, os.path.getsize(path) / 1e3))
    if h:
        ax[3].axhline(1000 * h, color="k", lw=0.8, ls=":", label="contact gap (1 cell)")
    ax[0].set_ylabel("centroid height (mm)")
    ax[1].set_ylabel("tilt of the thin axis (deg)")
    ax[2].set_ylabel("bending: mid-surface off its plane (mm)")
    ax[3].set_ylabel("gap (mm)")
    for k in (2, 3):
        ax[k].set_xlabel("t (s)")
    ax[0].legend(fontsize=8, title="markers: contact starts (v cylinder, [] base)", title_fontsize=7)
    ax[3].legend(fontsize=7, ncol=2)
    for x in ax:
        x.grid(alpha=0.3)
    if a.title:
        fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.output, dpi=80)
    fmt = lambda v, f="%.3f": "-" if v is None else f % v  # noqa: E731
    print("| run | first contact, cylinder (s) | second contact start, cylinder (s) | first contact, base (s) | "
          + " | ".join("tilt %.2f s (deg)" % tt for tt in PAPER_TIMES) + " | "
          + " | ".join("bending %.2f s (mm)" % tt for tt in PAPER_TIMES) + " |")
    print("|---" * (4 + 2 * len(PAPER_TIMES)) + "|")
    for label, f1, f2, fb, tilts, bends in rows:
        print("| %s | %s | %s | %s | %s | %s |" % (
            label, fmt(f1), fmt(f2), fmt(fb), " | ".join(fmt(v, "%.1f") for v in tilts),
            " | ".join(fmt(None if v is None else 1000 * v, "%.2f") for v in bends)))
    print()
    print("| run | t (s) | centroid y (mm) | centroid x (mm) | tilt (deg) | bending (mm) | gap cylinder (h) "
          "| gap base (h) | energy ratio | volume change (%) |")
    print("|---" * 10 + "|")
    for label, srows in states:
        for r in srows:
            print("| %s | %.2f | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f | %.2f | %.2f |" % ((label,) + r))
    if a.csv:  # rows of other runs (outputs no longer here) are kept; a run's new row replaces its old
        series.merge_csv(a.csv, results)
        print("plots.py: %d finished run(s) merged into %s" % (len(results), a.csv))
    if evs:
        print()
        print("| event | " + " | ".join(label for label, _ in evs) + " |")
        print("|---" * (1 + len(evs)) + "|")
        for q, (name, _) in enumerate(evs[0][1]):
            print("| %s | " % name + " | ".join(e[q][1] for _, e in evs) + " |")


def state_rows(cols, h):
    """The block's state at STATE_TIMES (those the run reached); gaps in cells of size h."""
    ts, pe0, nan = cols["t"], cols["solid_potential_energy"][0], float("nan")
    out = []
    for tt in STATE_TIMES:
        i = min(range(len(ts)), key=lambda q: abs(ts[q] - tt))   # one search per time
        if abs(ts[i] - tt) > 0.005:
            continue
        g = {k: cols[k][i] for k in STATE_KEYS}
        released = pe0 - g["solid_potential_energy"]
        ratio = (g["kinetic_energy"] + g["elastic_energy"]) / released if released > 0 else nan
        out.append((tt, 1000 * g["solid_cy"], 1000 * g["solid_cx"], g["solid_tilt_deg"], 1000 * g["solid_bending"],
                    g["solid_gap_obstacle0"] / h if h else nan, g["solid_gap_y-"] / h if h else nan,
                    ratio, 100 * g["volume_drift"]))
    return out

def first(ts, vals, test, t0=0.0):
    """(t, value) of the first sample at t >= t0 that passes test, or None."""
    for t, v in zip(ts, vals):
        if t >= t0 and test(v):
            return t, v
    return None


def slowing(ts, vy):
    """(t, vy) when the block's mean vy stops falling: it first rises 1 % of its size above its
    running minimum; None if it never does. The impact time of plots.py and waves.py."""
    low = 0.0
    for t, v in zip(ts, vy):
        low = min(low, v)
        if low < 0 and v > low + 0.01 * abs(low):
            return t, low
    return None


def first_peak(ts, vals, t0, rise=2.0, drop=0.8):
    """(t, value) of the first maximum after t0 of a quantity that has grown to `rise` times its
    value at t0 and then fallen below `drop` times that maximum; None if it never does. The
    bending of the impact itself: a stiff block's later oscillations can exceed it."""
    top, v0 = None, None
    for t, v in zip(ts, vals):
        if t < t0:
            continue
        if v0 is None:
            v0 = v
        if top is None or v > top[1]:
            top = (t, v)
        elif top[1] > rise * v0 and v < drop * top[1]:
            return top
    return None


def extreme(ts, vals, t0, t1, pick=max):
    """(t, value) of the largest (pick=max) or smallest value in [t0, t1], or None."""
    s = [(v, t) for t, v in zip(ts, vals) if t0 <= t <= t1]
    return None if not s else tuple(reversed(pick(s)))


EVENT_NAMES = ("mean vy stops falling (s; vy m/s)", "smallest gap to the cylinder in the impact (h, at s)",
               "lowest centroid (mm, at s)", "rebound (mm, to s)",
               "closest to the cylinder after the rebound, before the base (h, at s)",
               "first bending peak after the impact (mm, at s)",
               "slowing to peak bending (ms)", "base: gap < 2 h from (s)", "peak tilt (deg, at s)",
               "largest energy ratio (at s)", "energy ratio, volume change at the end (t s)")


def results_row(d, cols, summ):
    """Issue 22's falling-block table: one finished run (its directory and summary.json)."""
    cont = summ.get("solid_body", {}).get("contacts", {})
    ts, pe0 = cols["t"], cols["solid_potential_energy"][0]
    ratio = [(k + e) / (pe0 - p) if pe0 - p > 0 else 0.0
             for k, e, p in zip(cols["kinetic_energy"], cols["elastic_energy"], cols["solid_potential_energy"])]
    late = [r for t, r in zip(ts, ratio) if t >= 0.03]  # as events(): before, the released energy is ~0
    fmt = series.fmt
    ls = summ.get("level_set", {})
    sharp0 = ls.get("sharp_volume_initial")
    return dict(series.run_row(d, summ), **{
        "first_impact_s": fmt(cont.get("obstacle0", {}).get("first_contact_time")),
        "base_impact_s": fmt(cont.get("y-", {}).get("first_contact_time")),
        "peak_bending_mm": fmt(1000 * max(cols["solid_bending"]), "%.2f"),
        "max_energy_ratio": fmt(max(late) if late else None, "%.3f"),
        # The smoothed volume (what the global correction holds) and the sharp one (psi > 0).
        "volume_change_pct": fmt(100 * cols["volume_drift"][-1], "%.2f"),
        "sharp_volume_change_pct": fmt(100 * (ls["sharp_volume"] / sharp0 - 1) if sharp0 else None, "%.2f"),
        "free_fall_elastic_over_kinetic": fmt(free_fall_elastic(cols, summ), "%.2e"),
    })


def free_fall_elastic(cols, summ):
    """Issue 21's "no elastic energy before contact": the largest elastic / kinetic energy while
    the block's smoothing band (kappa h outside psi = 0, Eq. 4) is clear of the cylinder and the
    base, i.e. before anything but air can load it."""
    sb, ls = summ.get("solid_body", {}), summ.get("level_set", {})
    if not sb.get("contact_gap") or not ls.get("smoothing_cells"):
        return None
    band = ls["smoothing_cells"] * sb["contact_gap"] / sb.get("contact_gap_cells", 1.0)
    worst = None
    for e, k, g0, g1 in zip(cols["elastic_energy"], cols["kinetic_energy"], cols["solid_gap_obstacle0"],
                            cols["solid_gap_y-"]):
        if min(g0, g1) <= band:
            break
        if k > 0:
            worst = max(worst or 0.0, e / k)
    return worst


def events(cols, h):
    """The impact and what follows, by one rule for every run (gaps in cells of size h)."""
    ts = cols["t"]
    slow = slowing(ts, cols["solid_vy"])
    if not slow:   # no impact: nothing below is defined
        return [(name, "-") for name in EVENT_NAMES]
    t_s = slow[0]
    lowest = extreme(ts, cols["solid_cy"], t_s, t_s + 0.05, min)
    rebound = extreme(ts, cols["solid_cy"], lowest[0], lowest[0] + 0.08) if lowest else None
    bend = first_peak(ts, cols["solid_bending"], t_s)
    gap = [g / h for g in cols["solid_gap_obstacle0"]]
    closest = extreme(ts, gap, t_s, t_s + 0.05, min)
    base = first(ts, [g / h for g in cols["solid_gap_y-"]], lambda g: g < 2)
    # The paper's second hit (~0.2 s): how close the block comes back once it has rebounded.
    again = extreme(ts, gap, rebound[0], base[0] if base else ts[-1], min) if rebound else None
    pe0 = cols["solid_potential_energy"][0]
    ratio = [(k + e) / (pe0 - p) if pe0 - p > 0 else 0.0
             for k, e, p in zip(cols["kinetic_energy"], cols["elastic_energy"], cols["solid_potential_energy"])]
    rows = [
        ("mean vy stops falling (s; vy m/s)", "%.4f (%.3f)" % slow),
        ("smallest gap to the cylinder in the impact (h, at s)", "-" if not closest else "%.2f at %.4f" % closest[::-1]),
        ("lowest centroid (mm, at s)", "-" if not lowest else "%.1f at %.4f" % (1000 * lowest[1], lowest[0])),
        ("rebound (mm, to s)", "-" if not rebound else "%.1f to %.4f" % (1000 * (rebound[1] - lowest[1]), rebound[0])),
        ("closest to the cylinder after the rebound, before the base (h, at s)",
         "-" if not again else "%.2f at %.4f" % again[::-1]),
        ("first bending peak after the impact (mm, at s)", "-" if not bend else "%.2f at %.4f" % (1000 * bend[1], bend[0])),
        ("slowing to peak bending (ms)", "-" if not bend else "%.1f" % (1000 * (bend[0] - slow[0]))),
        ("base: gap < 2 h from (s)", "-" if not base else "%.4f" % base[0]),
        ("peak tilt (deg, at s)", "%.1f at %.3f" % extreme(ts, [abs(v) for v in cols["solid_tilt_deg"]], 0, ts[-1])[::-1]),
        ("largest energy ratio (at s)", "%.2f at %.3f" % extreme(ts, ratio, 0.03, ts[-1])[::-1]),
        ("energy ratio, volume change at the end (t s)", "%.2f, %.1f %% (%.3f)" % (ratio[-1], 100 * cols["volume_drift"][-1], ts[-1])),
    ]
    assert tuple(r[0] for r in rows) == EVENT_NAMES
    return rows


if __name__ == "__main__":
    main()
