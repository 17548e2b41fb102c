"""What a run wrote beside its fields (Python standard library only; numpy for probe_array):

- summary(outdir): summary.json (written at the end of a run: a run still going has none);
- timeseries(outdir): timeseries.csv, one column per quantity, one value per step;
- probe(outdir, name): probe_<name>.csv, the samples grouped by time; probe_array: all rows;
- read_csv, write_csv: the CSV tables the studies write (rows as dicts of strings).

OUTDIR may also be a run's digest (digest.py: <run id>.npz), which holds copies of these files.

    from voigt_post import series
    cols = series.timeseries("output/run")   # cols["t"], cols["solid_vy"], ... (floats)
"""
import csv
import fcntl
import json
import io
import os

from . import digest

_RAISE = object()


def _open(outdir, name):
    """OUTDIR/NAME as a text file, from the folder or from the digest's copy."""
    if digest.is_digest(outdir):
        data = digest.text(outdir, name)
        if data is None:
            raise FileNotFoundError("%s holds no %s" % (outdir, name))
        return io.StringIO(data, newline=None)
    return open(os.path.join(outdir, name), newline="")


def has(outdir, name):
    """Whether the run (folder or digest) has the file NAME."""
    if digest.is_digest(outdir):
        return digest.text(outdir, name) is not None
    return os.path.exists(os.path.join(outdir, name))


def summary(outdir, default=_RAISE):
    """OUTDIR/summary.json as a dict. Without `default` a missing or unreadable (half-written)
    file raises OSError or ValueError; with it, `default` is returned instead."""
    try:
        with _open(outdir, "summary.json") as f:
            return json.load(f)
    except (OSError, ValueError):
        if default is _RAISE:
            raise
        return default


def _rows(outdir, name):
    """Header and the rows with as many values as the header (a run still writing may have left
    its last line short)."""
    with _open(outdir, name) as f:
        r = csv.reader(f)
        head = next(r, [])
        return head, [row for row in r if len(row) == len(head)]


def timeseries(outdir):
    """OUTDIR/timeseries.csv as {column: [float per step]}. Values that are not numbers (empty
    cells) are left out of their column; a column of text (dt_reason) is left out."""
    head, rows = _rows(outdir, "timeseries.csv")
    cols = {}
    for row in rows:
        for k, v in zip(head, row):
            try:
                x = float(v)
            except ValueError:
                continue
            cols.setdefault(k, []).append(x)
    return cols


def probe_path(outdir, name):
    return os.path.join(outdir, "probe_%s.csv" % name)


def probe(outdir, name):
    """OUTDIR/probe_NAME.csv as {t: [row, ...]} in the order written, each row a dict of floats
    (t, s, x, y, z and the probed fields: psi, velocity_x, ...)."""
    head, rows = _rows(outdir, "probe_%s.csv" % name)
    out = {}
    for row in rows:
        r = dict(zip(head, (float(v) for v in row)))
        out.setdefault(r["t"], []).append(r)
    return out


def probe_array(path):
    """Every row of a probe file (a path, or (outdir or digest, name)) as a numpy structured array."""
    import numpy as np
    if isinstance(path, tuple):
        with _open(path[0], "probe_%s.csv" % path[1]) as f:
            return np.genfromtxt(f, delimiter=",", names=True)
    return np.genfromtxt(path, delimiter=",", names=True)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def write_csv(path, rows):
    """Rows (dicts) to PATH; the columns are every key in the order first seen."""
    keys = []
    for r in rows:
        for k in r:
            if k not in keys:
                keys.append(k)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow(r)


def fmt(v, f="%.4f"):
    """A CSV cell: "" for a missing value (None), else the value formatted."""
    return "" if v is None else f % v


def finished(summ):
    """Whether a summary.json says its run reached its end (summaries from before the "state"
    key: finished unless it says why it stopped)."""
    return bool(summ) and summ.get("state", "finished" if "stopped" not in summ else None) == "finished"


def run_row(d, summ):
    """The columns every case's results.csv starts with: one run (its folder and summary.json)."""
    el, ls, grid = summ.get("elasticity", {}), summ.get("level_set", {}), summ.get("grid", {})
    wall = summ.get("wall_seconds_total")  # null after a restart from an older checkpoint:
    if wall is None:                       # this segment's, then
        wall = summ.get("wall_seconds")
    return {
        "run_id": digest.run_id(d),
        "mu_S": fmt(el.get("shear_modulus"), "%g"),
        "model": el.get("fluid_side", ""),
        "volume_correction": ls.get("volume_correction", "none"),
        "grid": "x".join(str(n) for n in grid.get("cells", [])),
        "ranks": grid.get("ranks", ""),
        "t_end": fmt(summ.get("simulated_time")),
        "steps": summ.get("steps", ""),
        "wall_s": fmt(wall, "%.0f"),
    }


def merge_csv(path, rows, key="run_id"):
    """Rows (dicts) into the CSV at PATH: a row whose KEY is already there replaces that row in
    place, the others are appended (the last of equal keys wins); rows of PATH the new ones do
    not name are kept (e.g. runs whose outputs are no longer on this machine). New columns go
    last, blank in old rows. Read and rewritten under an exclusive lock on PATH itself, as
    cases/runs.py does with the ledger: two study jobs may end together."""
    if not rows:
        return
    fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o644)
    with os.fdopen(fd, "r+", newline="") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        old = list(csv.DictReader(f))
        new = {r[key]: r for r in rows}
        merged = [new.pop(r.get(key), r) for r in old]
        merged += list(new.values())
        keys = []
        for r in merged:
            keys += [k for k in r if k not in keys]
        f.seek(0)
        f.truncate()
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(merged)
