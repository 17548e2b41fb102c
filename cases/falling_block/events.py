"""The falling block's impact and what follows, by one rule for every run (plots.py prints them,
results.csv keeps them, table.py fills the paper-vs-Voigt table from that CSV).

measure(cols, h) reads a run's timeseries.csv (the `solid_body` columns, every step) with gaps in
cells of size h; results_row(d, cols, summ) is one results.csv row. Energy ratio = (kinetic
energy of block and air + elastic energy) / potential energy the block has released since
t = 0; without an energy source it stays <= 1.
"""

from voigt_post import series


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


def energy_ratio(cols):
    pe0 = cols["solid_potential_energy"][0]
    return [(k + e) / (pe0 - p) if pe0 - p > 0 else 0.0
            for k, e, p in zip(cols["kinetic_energy"], cols["elastic_energy"], cols["solid_potential_energy"])]


def measure(cols, h):
    """The events as numbers (s, mm, cells, degrees; None where a run has no such event)."""
    ts = cols["t"]
    ratio = energy_ratio(cols)
    tilt = extreme(ts, [abs(v) for v in cols["solid_tilt_deg"]], 0, ts[-1])
    top = extreme(ts, ratio, 0.03, ts[-1])   # before 0.03 s the released energy is ~0
    m = dict.fromkeys(("slowing_s", "slowing_vy", "impact_gap_h", "impact_gap_s", "lowest_mm", "lowest_s",
                       "rebound_mm", "rebound_s", "again_gap_h", "again_s", "bend_peak_mm", "bend_peak_s",
                       "base_2h_s"))
    m.update(peak_tilt_deg=tilt[1], peak_tilt_s=tilt[0], max_ratio=top[1] if top else None,
             max_ratio_s=top[0] if top else None, end_ratio=ratio[-1], end_tilt_deg=cols["solid_tilt_deg"][-1],
             end_volume_pct=100 * cols["volume_drift"][-1], t_end=ts[-1])
    slow = slowing(ts, cols["solid_vy"])
    if not slow:   # no impact: nothing else is defined
        return m
    t_s = slow[0]
    m["slowing_s"], m["slowing_vy"] = slow
    lowest = extreme(ts, cols["solid_cy"], t_s, t_s + 0.05, min)
    rebound = extreme(ts, cols["solid_cy"], lowest[0], lowest[0] + 0.08) if lowest else None
    bend = first_peak(ts, cols["solid_bending"], t_s)
    gap = [g / h for g in cols["solid_gap_obstacle0"]]
    closest = extreme(ts, gap, t_s, t_s + 0.05, min)
    base = first(ts, [g / h for g in cols["solid_gap_y-"]], lambda g: g < 2)
    # The paper's second hit (~0.2 s): how close the block comes back once it has rebounded.
    again = extreme(ts, gap, rebound[0], base[0] if base else ts[-1], min) if rebound else None
    if closest:
        m["impact_gap_s"], m["impact_gap_h"] = closest
    if lowest:
        m["lowest_s"], m["lowest_mm"] = lowest[0], 1000 * lowest[1]
    if rebound:
        m["rebound_s"], m["rebound_mm"] = rebound[0], 1000 * (rebound[1] - lowest[1])
    if again:
        m["again_s"], m["again_gap_h"] = again
    if bend:
        m["bend_peak_s"], m["bend_peak_mm"] = bend[0], 1000 * bend[1]
    if base:
        m["base_2h_s"] = base[0]
    return m


def _f(v, f):
    return "-" if v is None else f % v


def rows(m):
    """[(event, text)] of plots.py's events table."""
    pair = lambda a, b, f: "-" if m[a] is None else f % (m[a], m[b])  # noqa: E731
    return [
        ("mean vy stops falling (s; vy m/s)", pair("slowing_s", "slowing_vy", "%.4f (%.3f)")),
        ("smallest gap to the cylinder in the impact (h, at s)", pair("impact_gap_h", "impact_gap_s", "%.2f at %.4f")),
        ("lowest centroid (mm, at s)", pair("lowest_mm", "lowest_s", "%.1f at %.4f")),
        ("rebound (mm, to s)", pair("rebound_mm", "rebound_s", "%.1f to %.4f")),
        ("closest to the cylinder after the rebound, before the base (h, at s)", pair("again_gap_h", "again_s", "%.2f at %.4f")),
        ("first bending peak after the impact (mm, at s)", pair("bend_peak_mm", "bend_peak_s", "%.2f at %.4f")),
        ("slowing to peak bending (ms)",
         _f(None if m["bend_peak_s"] is None else 1000 * (m["bend_peak_s"] - m["slowing_s"]), "%.1f")),
        ("base: gap < 2 h from (s)", _f(m["base_2h_s"], "%.4f")),
        ("peak tilt (deg, at s)", "%.1f at %.3f" % (m["peak_tilt_deg"], m["peak_tilt_s"])),
        ("largest energy ratio (at s)", pair("max_ratio", "max_ratio_s", "%.2f at %.3f")),
        ("energy ratio, volume change at the end (t s)", "%.2f, %.1f %% (%.3f)" % (m["end_ratio"], m["end_volume_pct"], m["t_end"])),
    ]


def cell(summ):
    """The contact rule's cell size h (m) from summary.json, or None."""
    sb = summ.get("solid_body", {})
    return sb["contact_gap"] / sb.get("contact_gap_cells", 1.0) if sb.get("contact_gap") else None


def results_row(d, cols, summ):
    """Issue 22's falling-block table: one finished run (its directory or digest, summary.json)."""
    cont = summ.get("solid_body", {}).get("contacts", {})
    fmt = series.fmt
    ls = summ.get("level_set", {})
    sharp0 = ls.get("sharp_volume_initial")
    h = cell(summ)
    m = measure(cols, h) if h else {}
    top = extreme(cols["t"], energy_ratio(cols), 0.03, cols["t"][-1])   # as measure(), without h
    starts = cont.get("obstacle0", {}).get("contact_start_times", [])
    return dict(series.run_row(d, summ), **{
        "first_impact_s": fmt(cont.get("obstacle0", {}).get("first_contact_time")),
        "base_impact_s": fmt(cont.get("y-", {}).get("first_contact_time")),
        "peak_bending_mm": fmt(1000 * max(cols["solid_bending"]), "%.2f"),
        "max_energy_ratio": fmt(top[1] if top else None, "%.3f"),
        # The smoothed volume (what the global correction holds) and the sharp one (psi > 0).
        "volume_change_pct": fmt(100 * cols["volume_drift"][-1], "%.2f"),
        "sharp_volume_change_pct": fmt(100 * (ls["sharp_volume"] / sharp0 - 1) if sharp0 else None, "%.2f"),
        "free_fall_elastic_over_kinetic": fmt(free_fall_elastic(cols, summ), "%.2e"),
        # The events (measure()), so that the README's table can quote them from this file.
        "slowing_s": fmt(m.get("slowing_s")),
        "slowing_vy": fmt(m.get("slowing_vy"), "%.3f"),
        "impact_gap_h": fmt(m.get("impact_gap_h"), "%.2f"),
        "rebound_mm": fmt(m.get("rebound_mm"), "%.1f"),
        "rebound_to_s": fmt(m.get("rebound_s")),
        "second_contact_s": fmt(starts[1] if len(starts) > 1 else None),
        "closest_after_rebound_h": fmt(m.get("again_gap_h"), "%.2f"),
        "closest_after_rebound_s": fmt(m.get("again_s")),
        "first_bending_peak_mm": fmt(m.get("bend_peak_mm"), "%.2f"),
        "first_bending_peak_s": fmt(m.get("bend_peak_s")),
        "base_within_2h_s": fmt(m.get("base_2h_s")),
        "peak_tilt_deg": fmt(m.get("peak_tilt_deg"), "%.1f"),
        "peak_tilt_s": fmt(m.get("peak_tilt_s"), "%.3f"),
        "end_tilt_deg": fmt(m.get("end_tilt_deg"), "%.1f"),
        "end_energy_ratio": fmt(m.get("end_ratio"), "%.3f"),
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
