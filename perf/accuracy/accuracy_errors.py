"""The error measures of the accuracy study (perf/accuracy/run.py): each takes a run's output
folder and its summary.json and returns {"error": ..., and more columns of results.csv}."""
import math
import os

from voigt_post import couette, fields, scene_record, series
from voigt_post.formulas import taylor_green_rms


def h5_files(d):
    return sorted(os.path.join(d, f) for f in os.listdir(d) if f.startswith("fields_") and f.endswith(".h5"))


def tg_error(run_dir, summary):
    """RMS over owned nodes (periodic duplicates dropped) of u - exact, all 3 components."""
    import numpy as np
    u = fields.read(h5_files(run_dir)[-1], "velocity")  # (k, j, i, c)
    u = u[:-1, :-1, :-1, :]
    nk, nj, ni = u.shape[:3]
    x = np.arange(ni) * 2 * math.pi / ni
    y = np.arange(nj) * 2 * math.pi / nj
    rms, mx = taylor_green_rms(u, x, y, summary["simulated_time"])
    return {"error": rms, "error_max": mx}


ZALESAK_PERIMETER = 143.80  # the circle less the arc under the slot's mouth, + slot walls and top


def zalesak_error(run_dir, summary):
    import numpy as np
    files = h5_files(run_dir)
    psi0 = fields.read(files[0], "psi")
    psi = fields.read(files[-1], "psi")
    nz, ny, nx = psi.shape
    h = 100.0 / nx
    # sum over all cells * h^2 hz / (L * Lz) = sum / nz * h^2 / L
    err = float(np.abs((psi0 > 0).astype(float) - (psi > 0).astype(float)).sum()) / nz * h * h / ZALESAK_PERIMETER
    ls = summary.get("level_set", {})
    area = ls.get("sharp_volume", float("nan")) / ls.get("sharp_volume_initial", float("nan")) - 1
    harea = ls.get("volume", float("nan")) / ls.get("volume_initial", float("nan")) - 1
    return {"error": err, "error_cells": err / h, "area_change": area, "h_area_change": harea}


COUETTE_T = 2 * math.pi / 90.0    # forcing period of cases/elastic_couette (omega = 90 rad/s)
# Run length from rest, in periods. The start-up transient (the gel's free shear modes, near
# its quarter-wave resonance at 99 rad/s, decaying by radiation into the fluid) is gone after
# 7: measured over 10 periods, the last-period RMS error at 12 / 24 / 48 cells was
# 7.21e-3 / 5.82e-3 / 3.92e-3 after 6 periods, 7.25e-3 / 5.70e-3 / 3.63e-3 after 7, and
# 7.25e-3 / 5.75e-3 / 3.63e-3 after 8-10 (+-1 %). After 5 it is still 5-30 % high.
COUETTE_PERIODS = 7
COUETTE_SAMPLES = 8               # probe samples per period


def couette_error(run_dir, summary):
    """Elastic Couette from rest, COUETTE_PERIODS periods: u_x of the line probe at the nodes
    (x = z = h, y = 0 .. b, points = cells + 1) against the exact periodic (sharp-interface)
    state couette.Couette(**couette.params(the run's scene record)).u(y, t), as `couette.py
    --probe` does per sample (a run without a record: the case's elastic_couette.yaml).
    error: RMS over the nodes and the last period's 8 samples (t = (N - 1) T + T/8 .. N T;
    for a one-harmonic error that is the exact period mean), / V; error_max: max |e| / V over
    the same; error_prev: the RMS over the period before, to show how settled the run is."""
    import numpy as np
    c = couette.Couette(**couette.params(scene_record.scene_or(run_dir, couette.SCENE, "accuracy")))
    raw = series.probe_array((run_dir, "profile"))
    times = np.unique(raw["t"])

    def over(ts):
        # one row per (sample, point); runs before 2026-11-30 wrote the end time twice (the
        # last in-loop sample and the forced final one), which would weight it double
        r = raw[np.isin(raw["t"], ts)]
        _, first = np.unique(np.stack([r["t"], r["s"]], axis=1), axis=0, return_index=True)
        r = r[first]
        e = r["velocity_x"] - c.u(r["y"], r["t"])
        return float(np.sqrt(np.mean(e ** 2)) / c.V), float(np.abs(e).max() / c.V)

    n = COUETTE_SAMPLES
    rms, mx = over(times[-n:])
    prev, _ = over(times[-2 * n:-n])
    return {"error": rms, "error_max": mx, "error_prev": prev}
