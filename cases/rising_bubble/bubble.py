#!/usr/bin/env python3
"""The rising-bubble benchmark's quantities (Hysing et al. 2009, Sec. 3), from a run's
timeseries.csv, against the reference groups (reference/), for cases/rising_bubble/run.

    bubble.py finished DIR                            exit 0 if DIR's run reached its end time
    bubble.py row DIR --csv CSV --digests D           add DIR's row to CSV, its digest to D/
    bubble.py show DIR                                print DIR's quantities
    bubble.py table --csv CSV [--3d]                  the README's table: each grid's row beside
                                                      the reference groups'
    bubble.py figures --csv CSV --digests D -o OUT    OUT/case<c>.png (time series beside the
                                                      references, the shapes at t = 3) and
                                                      OUT/convergence.png

Quantities, per time step (solid_body's H-weighted measures of the psi > 0 phase, the bubble):
centroid y = solid_cy, rise velocity = solid_vy, circularity = pi d_a / P_b = 2 sqrt(pi A) / P
with A = volume_gas / L_z and P = interface_area / L_z (L_z the 2-D slab's depth; the box's
width and height from the run's scene record, scene.yaml).
Benchmark scalars: minimum circularity and its time, maximum rise velocity and its time (case
2: the maxima before and after t = 1.5), centroid y at t = 3."""
import argparse
import csv
import glob
import json
import math
import os
import sys

from voigt_post import scene_record

HERE = os.path.dirname(os.path.realpath(__file__))
REF = os.path.join(HERE, "reference")
COLUMNS = ["case", "n", "h", "t_end", "min_circularity", "t_min_circularity", "max_rise_velocity",
           "t_max_rise_velocity", "max_rise_velocity_2", "t_max_rise_velocity_2", "centroid_y_t3", "steps",
           "cell_steps", "wall_s", "ranks", "revision"]


def case_of(summary):
    return 2 if "case2" in os.path.basename(summary["scene"]) else 1


def is3d(d):
    return json.load(open(os.path.join(d, "summary.json")))["grid"]["cells"][2] > 2


def box(d):
    """(lo, hi) of run DIR's domain (x y z), from its scene record."""
    return scene_record.extent(scene_record.require(d, "bubble.py"))


def series(d):
    """t, circularity (3-D: sphericity), centroid y, rise velocity of run DIR (lists)."""
    with open(os.path.join(d, "timeseries.csv")) as f:
        rows = list(csv.DictReader(f))
    three = is3d(d)
    lo, hi = box(d)
    section = (hi[0] - lo[0]) * (hi[1] - lo[1])   # the slab's cross-section: 1 x 2 in the benchmark
    t, c, y, v = [], [], [], []
    for r in rows:
        vg, vl, area = float(r["volume_gas"]), float(r["volume_liquid"]), float(r["interface_area"])
        t.append(float(r["t"]))
        if three:  # the area of the sphere of the bubble's volume over the bubble's area
            c.append(math.pi ** (1 / 3.0) * (6 * vg) ** (2 / 3.0) / area)
            y.append(float(r["solid_cy"]))
            v.append(float(r["solid_vy"]))
            continue
        lz = (vg + vl) / section  # the box is section x L_z
        c.append(2 * math.sqrt(math.pi * vg / lz) / (area / lz))
        y.append(float(r["solid_cy"]))
        v.append(float(r["solid_vy"]))
    return t, c, y, v


def interp(t, f, at):
    for i in range(1, len(t)):
        if t[i] >= at:
            w = (at - t[i - 1]) / (t[i] - t[i - 1])
            return f[i - 1] + w * (f[i] - f[i - 1])
    return float("nan")


def argext(t, f, lo, hi, sign):
    """(value, time) of the largest sign * f over lo <= t <= hi."""
    best = None
    for ti, fi in zip(t, f):
        if lo <= ti <= hi and (best is None or sign * fi > sign * best[0]):
            best = (fi, ti)
    return best or (float("nan"), float("nan"))


def quantities(case, t, c, y, v):
    q = {}
    q["min_circularity"], q["t_min_circularity"] = argext(t, c, 0, 3, -1)
    split = 1.5 if case == 2 else 3.0
    q["max_rise_velocity"], q["t_max_rise_velocity"] = argext(t, v, 0, split, 1)
    if case == 2:
        q["max_rise_velocity_2"], q["t_max_rise_velocity_2"] = argext(t, v, split, 3, 1)
    q["centroid_y_t3"] = interp(t, y, 3.0)
    return q


def references(case, three=False):
    """{group: quantities} from reference/references.csv (the groups' finest grids; 3-D:
    references3d.csv)."""
    out = {}
    with open(os.path.join(REF, "references3d.csv" if three else "references.csv")) as f:
        for r in csv.DictReader(f):
            if int(r["case"]) == case:
                out[r["group"]] = {k: float(x) for k, x in r.items() if k not in ("case", "group", "file") and x}
    return out


def reference_series(case):
    """t, circularity, centroid y, rise velocity of the MooNMD reference file (FeatFlow)."""
    t, c, y, v = [], [], [], []
    with open(os.path.join(REF, "c%dg3l4.txt" % case)) as f:
        for line in f:
            p = [float(x) for x in line.split()]
            if p and p[0] <= 3.0:
                t.append(p[0]), c.append(p[2]), y.append(p[3]), v.append(p[4])
    return t, c, y, v


def final_contour(d):
    """The psi = 0 contour of DIR's last field file (x, y lists; 3-D: in the plane z = 1/2), or None."""
    files = sorted(glob.glob(os.path.join(d, "fields_*.h5")))
    if not files:
        return None
    import h5py
    import numpy as np
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    full = h5py.File(files[-1], "r")["psi"]
    psi = full[full.shape[0] // 2 if full.shape[0] > 2 else 0]  # 3-D: the mid-plane z = 1/2
    lo, hi = box(d)
    n = psi.shape[1]
    x = lo[0] + (np.arange(n) + 0.5) * (hi[0] - lo[0]) / n
    yy = lo[1] + (np.arange(psi.shape[0]) + 0.5) * (hi[1] - lo[1]) / psi.shape[0]
    segs = plt.contour(x, yy, psi, [0]).allsegs[0]
    plt.close("all")
    seg = max(segs, key=len)
    return [round(float(a), 5) for a in seg[:, 0]], [round(float(b), 5) for b in seg[:, 1]]


def cmd_row(a):
    s = json.load(open(os.path.join(a.dir, "summary.json")))
    case = case_of(s)
    n = s["grid"]["cells"][0]
    t, c, y, v = series(a.dir)
    q = quantities(case, t, c, y, v)
    cells = s["grid"]["cells"][0] * s["grid"]["cells"][1] * s["grid"]["cells"][2]
    row = {"case": case, "n": n, "h": "1/%d" % n, "t_end": round(t[-1], 6), "steps": s["steps"],
           "cell_steps": "%.3g" % (cells * s["steps"]),
           "wall_s": round(s["wall_seconds_total"], 1), "ranks": s["grid"].get("ranks_total", 1),
           "revision": s["revision"]}
    row.update({k: ("%.4f" % x if isinstance(x, float) else x) for k, x in q.items()})
    rows = []
    if os.path.exists(a.csv):
        rows = [r for r in csv.DictReader(open(a.csv)) if (int(r["case"]), int(r["n"])) != (case, n)]
    rows.append(row)
    rows.sort(key=lambda r: (int(r["case"]), int(r["n"])))
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    # The digest: the series every 0.01 in t and the final shape.
    os.makedirs(a.digests, exist_ok=True)
    keep, last = [], -1.0
    for i, ti in enumerate(t):
        if ti - last >= 0.01 - 1e-12 or i == len(t) - 1:
            keep.append(i)
            last = ti
    dig = {"case": case, "n": n, "t": [t[i] for i in keep], "circularity": [round(c[i], 6) for i in keep],
           "centroid_y": [round(y[i], 6) for i in keep], "rise_velocity": [round(v[i], 6) for i in keep],
           "shape_t": t[-1], "shape": final_contour(a.dir)}
    with open(os.path.join(a.digests, "case%d_%d.json" % (case, n)), "w") as f:
        json.dump(dig, f, separators=(",", ":"))
    print("case %d, h = 1/%d: %s" % (case, n, ", ".join("%s %s" % (k, row[k]) for k in q)))


def cmd_show(a):
    s = json.load(open(os.path.join(a.dir, "summary.json")))
    case = case_of(s)
    q = quantities(case, *series(a.dir))
    print("case %d%s (%s):" % (case, ", 3-D (circularity: sphericity)" if is3d(a.dir) else "", a.dir))
    refs = references(case, is3d(a.dir))
    for k, x in q.items():
        print("  %-22s %.4f   %s" % (k, x, "  ".join("%s %.4f" % (g, r[k]) for g, r in refs.items() if k in r)))


def cmd_table(a):
    keys = ["min_circularity", "t_min_circularity", "max_rise_velocity", "t_max_rise_velocity",
            "max_rise_velocity_2", "t_max_rise_velocity_2", "centroid_y_t3"]
    heads = ["c min", "t(c min)", "V max", "t(V max)", "V2 max", "t(V2 max)", "y(t = 3)"]
    rows = list(csv.DictReader(open(a.csv)))
    for case in sorted({int(r["case"]) for r in rows}):
        ks = [k for k in keys if any(r.get(k) for r in rows if int(r["case"]) == case)]
        hs = [heads[keys.index(k)] for k in ks]
        print("Test case %d%s:\n" % (case, " (3-D; c: sphericity)" if a.three else ""))
        print("| | " + " | ".join(hs) + " | cell-steps | wall s |")
        print("|---" * (len(hs) + 3) + "|")
        for r in sorted((r for r in rows if int(r["case"]) == case), key=lambda r: int(r["n"])):
            print("| Voigt h = %s | %s | %s | %s |" % (r["h"], " | ".join(r[k] for k in ks), r["cell_steps"], r["wall_s"]))
        for g, q in references(case, a.three).items():
            print("| %s | %s | | |" % (g, " | ".join("%.4f" % q[k] if k in q else "" for k in ks)))
        print()


def cmd_finished(a):
    s = json.load(open(os.path.join(a.dir, "summary.json")))
    sys.exit(0 if s.get("state") == "finished" else 1)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = p.add_subparsers(dest="cmd", required=True)
    for name in ("finished", "show"):
        sub.add_parser(name).add_argument("dir")
    r = sub.add_parser("row")
    r.add_argument("dir")
    r.add_argument("--csv", required=True)
    r.add_argument("--digests", required=True)
    tb = sub.add_parser("table")
    tb.add_argument("--csv", required=True)
    tb.add_argument("--3d", dest="three", action="store_true")
    f = sub.add_parser("figures")
    f.add_argument("--csv", required=True)
    f.add_argument("--digests", required=True)
    f.add_argument("-o", required=True)
    a = p.parse_args()
    if a.cmd == "figures":
        from figures import figures   # beside this script (its folder leads sys.path)
        figures(a, references, reference_series)
    else:
        {"finished": cmd_finished, "show": cmd_show, "row": cmd_row, "table": cmd_table}[a.cmd](a)


if __name__ == "__main__":
    main()
