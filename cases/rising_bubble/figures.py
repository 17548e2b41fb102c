"""Figures of the rising-bubble study (bubble.py figures): per case the circularity, centroid
and rise velocity against time at each grid beside the MooNMD reference series, and the shapes
at t = 3 beside the reference shape; then the benchmark scalars' errors against the TP2D
values over h and over wall time (the accuracy and its price)."""
import csv
import glob
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.realpath(__file__))
KEYS = [("min_circularity", "min circularity"), ("max_rise_velocity", "max rise velocity"),
        ("centroid_y_t3", "centroid y at t = 3")]
KEYS2 = [("max_rise_velocity", "first max rise velocity"), ("max_rise_velocity_2", "second max rise velocity"),
         ("centroid_y_t3", "centroid y at t = 3")]


def digests(d, case):
    out = []
    for f in sorted(glob.glob(os.path.join(d, "case%d_*.json" % case))):
        out.append(json.load(open(f)))
    return sorted(out, key=lambda g: g["n"])


# Variants drawn beside the defaults' runs (run --variant NAME: digests_NAME/), dashed.
VARIANTS = [("semi_implicit", "semi-implicit viscosity")]


def plot_runs(ax, digs, prefix="Voigt", style="-"):
    """Each run's circularity, centroid and rise velocity series and its final shape."""
    for g in digs:
        lab = "%s h = 1/%d" % (prefix, g["n"])
        ax[0].plot(g["t"], g["circularity"], style, label=lab)
        ax[1].plot(g["t"], g["centroid_y"], style, label=lab)
        ax[2].plot(g["t"], g["rise_velocity"], style, label=lab)
        if g.get("shape"):
            ax[3].plot(g["shape"][0], g["shape"][1], style, label=lab + " (t = %.2f)" % g["shape_t"])


def case_figure(case, digs, ref_series, path, variants=()):
    fig, ax = plt.subplots(1, 4, figsize=(17, 4.2))
    rt, rc, ry, rv = ref_series(case)
    for a, f, name in zip(ax[:3], (rc, ry, rv), ("circularity", "centroid y", "rise velocity")):
        a.plot(rt, f, "k-", lw=2.5, alpha=0.35, label="MooNMD (reference)")
        a.set_xlabel("t")
        a.set_title(name)
    plot_runs(ax, digs)
    for name, vdigs in variants:
        plot_runs(ax, vdigs, name, "--")
    ref = os.path.join(HERE, "reference", "c%dg3l4s.txt" % case)
    xs, ys = [], []
    for line in open(ref):
        p = line.split()
        if len(p) >= 2:
            xs.append(float(p[0])), ys.append(float(p[1]))
    ax[3].plot(xs, ys, "k.", ms=1.5, alpha=0.5, label="MooNMD (reference)")
    ax[3].set_aspect("equal")
    ax[3].set_xlim(0, 1)
    ax[3].set_title("shape at t = 3")
    ax[0].legend(fontsize=7)
    ax[3].legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.suptitle("Rising bubble, Hysing et al. (2009) test case %d" % case)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def convergence_figure(rows, refs, path):
    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    for case, col in ((1, 0), (2, 1)):
        rs = sorted([r for r in rows if int(r["case"]) == case], key=lambda r: int(r["n"]))
        if not rs:
            continue
        tp = refs(case)["TP2D"]
        keys = KEYS if case == 1 else KEYS2  # case 2's minimum circularity has not converged
        for key, name in keys:
            err = [abs(float(r[key]) - tp[key]) / tp[key] for r in rs]
            h = [1.0 / int(r["n"]) for r in rs]
            w = [float(r["cell_steps"]) for r in rs]
            ax[0][col].loglog(h, err, "o-", label=name)
            ax[1][col].loglog(w, err, "o-", label=name)
        hh = [1.0 / int(r["n"]) for r in rs]
        ax[0][col].loglog(hh, [0.05 * (x / hh[0]) for x in hh], "k:", label="first order")
        ax[0][col].loglog(hh, [0.05 * (x / hh[0]) ** 2 for x in hh], "k--", label="second order")
        ax[0][col].set_xlabel("h")
        ax[1][col].set_xlabel("cell-steps (the work; wall seconds in results.csv)")
        for a in ax[:, col]:
            a.set_ylabel("|relative error| vs TP2D")
            a.set_title("test case %d" % case)
            a.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def figure3d(digs, refs, path):
    """The 3-D bubble: the series at each grid, the reference groups' extremes as markers."""
    fig, ax = plt.subplots(1, 4, figsize=(17, 4.2))
    plot_runs(ax, digs)
    for name, r in refs.items():
        ax[0].plot([r["t_min_circularity"]], [r["min_circularity"]], "x", label=name + " (min)")
        ax[1].plot([3.0], [r["centroid_y_t3"]], "x", label=name)
        ax[2].plot([r["t_max_rise_velocity"]], [r["max_rise_velocity"]], "x", label=name + " (max)")
    for a, name in zip(ax, ("sphericity", "centroid y", "rise velocity", "section z = 1/2 at t = 3")):
        a.set_title(name)
        a.legend(fontsize=6)
    ax[3].set_aspect("equal")
    fig.suptitle("3-D rising bubble, Adelsberger et al. (2014) test case 1")
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def figures(a, refs, ref_series):
    rows = list(csv.DictReader(open(a.csv))) if os.path.exists(a.csv) else []
    base = os.path.dirname(a.digests.rstrip("/"))
    for case in (1, 2):
        digs = digests(a.digests, case)
        variants = [(label, digests(os.path.join(base, "digests_" + v), case)) for v, label in VARIANTS
                    if os.path.isdir(os.path.join(base, "digests_" + v))]
        if digs:
            case_figure(case, digs, ref_series, os.path.join(a.o, "case%d.png" % case), [x for x in variants if x[1]])
    if rows:
        convergence_figure(rows, refs, os.path.join(a.o, "convergence.png"))
    d3 = os.path.join(os.path.dirname(a.digests.rstrip("/")), "digests3d")
    digs = digests(d3, 1) if os.path.isdir(d3) else []
    if digs:
        figure3d(digs, refs(1, True), os.path.join(a.o, "bubble3d.png"))
