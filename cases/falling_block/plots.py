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

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from voigt_post import digest, series  # noqa: E402
from voigt_post.xdmf import frames  # noqa: E402
from events import cell, measure, results_row, rows as event_rows  # noqa: E402

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
        h_run = cell(summ)
        if h_run:
            h = sb["contact_gap"]
        elif not summ:  # a run still going: the grid's h
            h_run = frames(d)[0].spacing[0]
        states.append((label, state_rows(cols, h_run)))
        if h_run:
            evs.append((label, event_rows(measure(cols, h_run))))
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


if __name__ == "__main__":
    main()
