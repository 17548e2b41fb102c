"""What Figs. 4-8 of the porous bed (cases/porous_bed/plots.py, outlet.py) read from one run:
from its output folder (RunDir) or from its digest (Digest), a small committed .npz with the
same numbers at the run's end, and the scene it ran (scene()).

Full-grid runs take hours and their folders live outside the work tree, on a machine that a
later job may not get back (2026-12-05: all five 50 x 150 x 50 folders were lost with the
machine). The digest keeps what the figures and results.csv need, ~0.1 MB a run, in
cases/porous_bed/digests/<run id>.npz (plots.py --digests DIR writes one per finished run),
so the figures of every finished run can be drawn again on any machine. A digest holds the
run's scene record too (file:scene.yaml, as voigt_post/digest.py's; since 2026-12-08).
Numpy; h5py or h5dump for a folder's fields; PyYAML for the scene.
"""
import json
import os
import sys

import numpy as np

from . import fields, scene_record, series
from .launch import REPO
from .xdmf import frames

CASE = os.path.join(REPO, "cases", "porous_bed")
SCENE = os.path.join(CASE, "porous_bed.yaml")         # the case's scene file
PACKING = os.path.join(CASE, "packing.json")           # its packing's record (voidages, diameter)
Y0, Y1 = 0.10, 0.25  # the paper's bed interior
MAX_SERIES = 2000    # centroid samples kept in a digest (thinned evenly; Fig. 8 draws a line)


def scene(sources, who):
    """The scene of the first of SOURCES (run folders or digests) that has a record; else the
    case's porous_bed.yaml (digests written before 2026-12-08, runs before 2026-12-02), with a
    note on stderr from WHO."""
    for src in sources:
        sc = scene_record.scene(src)
        if sc is not None:
            return sc
    print("%s: no scene record in %s: the gas, inflow and gravity of %s" % (who, ", ".join(sources), SCENE),
          file=sys.stderr)
    return scene_record.load(SCENE)


def _section_gradient(pbar, dy):
    y = (np.arange(pbar.size) + 0.5) * dy
    sel = (y >= Y0) & (y <= Y1)
    return float(np.mean(-np.gradient(pbar, y)[sel]))


class RunDir:
    """A run's output folder; `at`: use the last field output at or before this time."""

    def __init__(self, d, at=None):
        self.d, self.at = d, at
        self.run_id = os.path.basename(os.path.normpath(d))

    def midline(self):
        """(t, y, p) on the vertical midline: the probe at its last time, or with `at` the
        pressure of that output (mean of the four cell columns around x = z = 5.5 cm)."""
        if self.at is not None:
            t, path, _, _, sp = frames(self.d, self.at)[-1]
            p = fields.read(path, "pressure")          # (z, y, x), cell centres
            nz, ny, nx = p.shape
            col = p[nz // 2 - 1:nz // 2 + 1, :, nx // 2 - 1:nx // 2 + 1].mean(axis=(0, 2))
            return t, (np.arange(ny) + 0.5) * sp[1], col
        rows = series.probe(self.d, "midline")
        t = max(rows)
        y, p = np.array(sorted((r["y"], r["pressure"]) for r in rows[t])).T
        return t, y, p

    def centroid(self):
        cols = series.timeseries(self.d)
        return np.array(cols["t"]), np.array(cols["solid_cy"])

    def section_gradient(self):
        """(t, mean -dp/dy over y = 0.10-0.25 m) of the pressure averaged over each cross-section
        in the last field output at or before `at`: the midline's measure without its steps
        where the line crosses a sphere that holds elastic stress."""
        t, path, _, _, sp = frames(self.d, self.at)[-1]
        return t, _section_gradient(fields.read(path, "pressure").mean(axis=(0, 2)), sp[1])

    def slices(self):
        """(spacing, [(t, pressure, psi) mid-plane z slices of the first, middle and last output])."""
        fr = frames(self.d, self.at)
        picks = [fr[0], fr[len(fr) // 2], fr[-1]]
        return fr[-1][4], [(q[0], fields.mid_z(q[1], "pressure"), fields.mid_z(q[1], "psi")) for q in picks]

    def summary(self):
        return series.summary(self.d, {})


class Digest:
    """A digest written by write_digest: the same methods as RunDir, at the run's end only."""

    def __init__(self, path):
        z = np.load(path)
        self.z = {k: z[k] for k in z.files}
        self.run_id = str(self.z["run_id"])

    def midline(self):
        return float(self.z["midline_t"]), self.z["midline_y"], self.z["midline_p"]

    def centroid(self):
        return self.z["centroid_t"], self.z["centroid_cy"]

    def section_gradient(self):
        return float(self.z["section_t"]), float(self.z["section_gradient"])

    def slices(self):
        t = self.z["slice_t"]
        return self.z["spacing"], [(float(t[n]), self.z["slice_p"][n], self.z["slice_psi"][n]) for n in range(len(t))]

    def summary(self):
        return json.loads(str(self.z["summary"]))


def load(path, at=None):
    """A run folder or a digest (.npz)."""
    if path.endswith(".npz"):
        if at is not None:
            raise SystemExit("plots.py: --time needs run folders; %s is a digest (the run's end only)" % path)
        return Digest(path)
    return RunDir(path, at)


def thin(n):
    """Indices of the n centroid samples a digest keeps: all of them up to MAX_SERIES, else that many
    evenly spread (thin(len) of a digest's series keeps it whole, so a run and its digest agree)."""
    return np.unique(np.linspace(0, n - 1, min(n, MAX_SERIES)).astype(int))


def peak_rise(t, cy):
    """(largest rise of the centroid above its start in mm, its time) over the kept samples."""
    keep = thin(len(t))
    j = keep[int(np.argmax(cy[keep]))]
    return 1000 * (cy[j] - cy[0]), t[j]


def write_digest(run, path):
    """The numbers plots.py draws from `run` (a RunDir at its end) into `path` (.npz). Slices in
    float32 (a figure's colour scale); the midline, gradients and centroid in double."""
    mt, my, mp = run.midline()
    st, sg = run.section_gradient()
    summ = run.summary()
    z = dict(run_id=run.run_id, summary=json.dumps(summ), midline_t=mt, midline_y=my, midline_p=mp,
             section_t=st, section_gradient=sg)
    record = scene_record.record_path(run.d)
    if record:
        with open(record) as f:
            z["file:scene.yaml"] = np.frombuffer(f.read().encode(), dtype=np.uint8)
    if "elasticity" in summ:  # a bed (rigid_bed.py's fixed spheres have no centroid, no psi)
        ct, cy = run.centroid()
        keep = thin(len(ct))
        sp, sl = run.slices()
        z.update(centroid_t=ct[keep], centroid_cy=cy[keep], spacing=np.array(sp),
                 slice_t=np.array([q[0] for q in sl]), slice_p=np.array([q[1] for q in sl], dtype=np.float32),
                 slice_psi=np.array([q[2] for q in sl], dtype=np.float32))
    tmp = path + ".tmp.npz"
    np.savez_compressed(tmp, **z)
    os.replace(tmp, path)
