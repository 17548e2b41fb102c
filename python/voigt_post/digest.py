"""A run's digest: what its figures and results rows need, in one small .npz that is committed
beside the case's ledger, so the figures of a finished run can be drawn again after the machine
it ran on is gone (full runs take hours and their folders live outside the work tree).

It holds the run's small files as written (summary.json, timeseries.csv, the scene record,
probe_*.csv, each probe cut to a time window when asked) and, at chosen output times, the
level set psi and one colour field (log10_S2) cropped to the box of cells within PAD cells of
psi >= 0, psi clipped to +-PAD h and the colour zero beyond that band (the surface reads
psi's sign and gradient there, its colour is sampled one cell inside), both float16 (psi to
~1e-3 of PAD h, the colour to 3 digits): pictures, not numbers. The surface psi = 0 and its
colour come out as from the whole field to that precision.

The readers take a digest wherever they take an output folder: series.summary / timeseries /
probe, scene_record.scene, picture.draw (frames() below), e.g.

    python3 -m voigt_post.digest RUN_DIR out.npz --times 0.04 0.08 --probe impact 0.03 0.15
    series.timeseries("out.npz")["solid_vy"]
"""
import argparse
import collections
import io
import os

PAD = 2                      # cells kept around psi = 0: the colour is sampled one cell inside,
                             # interpolated between that cell and the next
SUFFIX = ".npz"

# One stored output: the whole grid's origin, spacing and cells (x y z) and the crop's arrays
# in the file's (z, y, x) order with the crop's own origin.
Frame = collections.namedtuple("Frame", "t cells origin spacing crop_origin psi colour field")


def is_digest(path):
    return str(path).endswith(SUFFIX) and os.path.isfile(path)


def run_id(path):
    """The run id of a folder or of its digest (<run id>.npz)."""
    base = os.path.basename(os.path.normpath(path))
    return base[:-len(SUFFIX)] if base.endswith(SUFFIX) else base


_cache = {}


def _load(path):
    import numpy as np
    key = (os.path.abspath(path), os.path.getmtime(path))
    if key not in _cache:
        with np.load(path, allow_pickle=False) as z:
            _cache[key] = {k: z[k] for k in z.files}
    return _cache[key]


def files(path):
    """Names of the run's files the digest holds."""
    return sorted(k[5:] for k in _load(path) if k.startswith("file:"))


def text(path, name):
    """The digest's copy of the run's file NAME (str), or None when it has none."""
    a = _load(path).get("file:" + name)
    return None if a is None else a.tobytes().decode()


def frames(path):
    """The stored outputs, in time order."""
    import json
    d = _load(path)
    out = []
    for m in json.loads(text(path, "digest_frames.json") or "[]"):
        i = m["index"]
        out.append(Frame(m["t"], m["cells"], m["origin"], m["spacing"], m["crop_origin"],
                         d["psi_%d" % i].astype("float64"),
                         d["colour_%d" % i].astype("float64") if "colour_%d" % i in d else None, m["field"]))
    return out


def _crop(psi, h, pad):
    """Slices (z, y, x) of the box around psi >= -pad h, widened by pad cells."""
    import numpy as np
    inside = np.argwhere(psi >= -pad * h)
    if inside.size == 0:
        return tuple(slice(0, 0) for _ in psi.shape)
    lo = np.maximum(inside.min(axis=0) - pad, 0)
    hi = np.minimum(inside.max(axis=0) + pad + 1, psi.shape)
    return tuple(slice(a, b) for a, b in zip(lo, hi))


def _windowed(csv_text, window):
    """The header and the rows of a probe CSV whose first column (t) lies in [t0, t1]."""
    lines = csv_text.splitlines(keepends=True)
    keep = lines[:1]
    for line in lines[1:]:
        try:
            t = float(line.split(",", 1)[0])
        except ValueError:
            continue
        if window[0] - 1e-12 <= t <= window[1] + 1e-12:
            keep.append(line)
    return "".join(keep)


def write(outdir, dest, times=(), field="log10_S2", probes=None, pad=PAD):
    """The digest of run folder OUTDIR to DEST (.npz, written whole then renamed): its small
    files, its probes (probes: None for all, whole; else only those named, {name: (t0, t1) or
    None}), and the outputs nearest `times`."""
    import json
    import numpy as np
    from . import fields, scene_record
    from .xdmf import frames as xdmf_frames
    arrays = {}

    def keep(name, data):
        arrays["file:" + name] = np.frombuffer(data.encode(), dtype=np.uint8)

    for name in sorted(os.listdir(outdir)):
        if name in ("summary.json", "timeseries.csv") or (name.startswith("probe_") and name.endswith(".csv")):
            with open(os.path.join(outdir, name)) as f:
                data = f.read()
            probe = name[len("probe_"):-len(".csv")] if name.startswith("probe_") else None
            if probe is not None and probes is not None:
                if probe not in probes:
                    continue
                if probes[probe] is not None:
                    data = _windowed(data, probes[probe])
            keep(name, data)
    record = scene_record.record_path(outdir)
    if record:
        with open(record) as f:
            keep("scene.yaml", f.read())
    meta, done = [], set()
    fr = xdmf_frames(outdir) if times else []
    for t in times:
        f = min(fr, key=lambda g: abs(g.t - t))
        if f.t in done:
            continue
        done.add(f.t)
        h = min(f.spacing)
        psi = fields.read(f.path, "psi")
        box = _crop(psi, h, pad)
        psi = psi[box]
        far = np.abs(psi) > pad * h     # what the surface and its colour do not read: constant,
        i = len(meta)                   # so that it compresses to nothing
        arrays["psi_%d" % i] = np.clip(psi, -pad * h, pad * h).astype(np.float16)
        has = field and field in fields.names(f.path)
        if has:
            col = fields.read(f.path, field)
            col = (col if col.ndim == 3 else np.linalg.norm(col, axis=-1))[box]
            arrays["colour_%d" % i] = np.where(far, 0.0, col).astype(np.float16)
        start = [b.start for b in box][::-1]            # x y z
        meta.append({"index": i, "t": f.t, "cells": f.cells, "origin": f.origin, "spacing": f.spacing,
                     "crop_origin": [o + s * n for o, s, n in zip(f.origin, f.spacing, start)],
                     "field": field if has else ""})
    keep("digest_frames.json", json.dumps(meta))
    tmp = dest + ".part"
    with open(tmp, "wb") as f:
        buf = io.BytesIO()
        np.savez_compressed(buf, **arrays)
        f.write(buf.getvalue())
    os.replace(tmp, dest)
    return dest


def main(argv=None):
    ap = argparse.ArgumentParser(prog="digest", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run", help="the run's output folder")
    ap.add_argument("dest", help="the digest to write (.npz)")
    ap.add_argument("--times", nargs="*", type=float, default=[], help="outputs to keep (the nearest to each)")
    ap.add_argument("--field", default="log10_S2", help="colour field kept with psi")
    ap.add_argument("--probe", nargs="+", action="append", default=[], metavar="NAME [T0 T1]",
                    help="keep this probe (all of it, or its rows with T0 <= t <= T1); default: every probe")
    a = ap.parse_args(argv)
    if not a.dest.endswith(SUFFIX):
        ap.error("the digest's name must end in %s" % SUFFIX)
    if any(len(p) not in (1, 3) for p in a.probe):
        ap.error("--probe NAME or --probe NAME T0 T1")
    probes = {p[0]: (float(p[1]), float(p[2])) if len(p) == 3 else None for p in a.probe} or None
    write(a.run, a.dest, a.times, a.field, probes)
    print("wrote %s (%.0f kB)" % (a.dest, os.path.getsize(a.dest) / 1e3))


if __name__ == "__main__":
    main()
