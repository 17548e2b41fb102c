#!/usr/bin/env python3
"""Centroid paths of cavity_disk runs (solid_cx, solid_cy from timeseries.csv), the first
loop's largest x after t = 4, and a figure.

    paths.py DIR [DIR ...] [-o PNG]      each DIR a `voigt run` of cavity_disk.yaml
"""
import argparse
import csv
import os


def path(d):
    r = list(csv.DictReader(open(os.path.join(d, "timeseries.csv"))))
    return [float(x["t"]) for x in r], [float(x["solid_cx"]) for x in r], [float(x["solid_cy"]) for x in r]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("-o")
    a = ap.parse_args()
    runs = []
    for d in a.dirs:
        t, x, y = path(d)
        i = max((i for i in range(len(t)) if 4 < t[i] < 8), key=lambda i: x[i])
        print("%s: largest x after t = 4: %.4f at t = %.2f; at t = %.2f: (%.4f, %.4f)" % (d, x[i], t[i], t[-1], x[-1], y[-1]))
        runs.append((os.path.basename(d.rstrip("/")), x, y))
    if a.o:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(5, 5))
        for name, x, y in runs:
            ax.plot(x, y, label=name)
        ax.axvline(0.70, color="k", ls=":", lw=0.8, label="x = 0.70 (references' turn)")
        ax.set_xlim(0, 1), ax.set_ylim(0, 1), ax.set_aspect("equal")
        ax.set_xlabel("x"), ax.set_ylabel("y"), ax.legend(fontsize=7)
        ax.set_title("disk centroid, t = 0-8, 64^2")
        fig.tight_layout()
        fig.savefig(a.o, dpi=90)


if __name__ == "__main__":
    main()
