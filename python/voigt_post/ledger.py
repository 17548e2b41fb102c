"""The run ledger of a study (cases/<name>/runs.csv, committed): one row per run, so how far
each long run got is known even when the machine that ran it is gone. Written by cases/study.sh
through cases/runs.py (its command line); the cases' table.py quote it.

revisions: the builds (commits) that ran its segments, from summary.json.
States: running, wall_limit (voigt exit 75), stopped (SIGINT/SIGTERM), finished, failed.
to_finish_s: for a run that stopped before its end, the wall seconds its last segment's pace
(seconds per step, mean dt of its last 100 steps) needs to reach the end time (issue 22 item 5).
Standard library only."""
import csv
import datetime
import fcntl
import os
import re

from . import series

COLUMNS = ["run_id", "modulus", "model", "grid", "ranks", "t_reached", "steps", "wall_s", "state", "to_finish_s",
           "updated_utc", "revisions"]
EXIT_STATE = {0: "finished", 75: "wall_limit", 130: "stopped", 143: "stopped"}


def summary(path):
    return series.summary(path, None)


def state(path):
    """finished: its summary says so (no "stopped": runs before the "state" key); failed: a
    blow-up; unfinished: a checkpoint to continue from; new: nothing to continue."""
    s = summary(path)
    if s is not None:
        st = s.get("state", "finished" if "stopped" not in s else None)
        if st in ("finished", "blow_up"):
            return "finished" if st == "finished" else "failed"
    return "unfinished" if os.path.exists(os.path.join(path, "latest")) else "new"


def update(ledger, rid, values):
    """Sets the row's values (a new row if none), under a lock: runs may end together."""
    fd = os.open(ledger, os.O_RDWR | os.O_CREAT, 0o644)
    with os.fdopen(fd, "r+", newline="") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        rows = [r for r in csv.DictReader(f)]
        if rows and "run_id" not in rows[0]:
            rows = []  # a table of the older format (cells, wall_seconds, ...): replaced
        row = next((r for r in rows if r["run_id"] == rid), None)
        if row is None:
            row = {c: "" for c in COLUMNS}
            row["run_id"] = rid
            rows.append(row)
        row.update(values)
        row["updated_utc"] = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
        f.seek(0)
        f.truncate()
        w = csv.DictWriter(f, COLUMNS, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def end_time(path, s):
    """The time the run runs to: summary.json's end_time, else (Voigt before 2026-12-04) the
    run's own scene record PATH/scene.yaml: its "# --end-time" line, or time.end as Voigt's
    YAML emitter writes it (block style, the keys of time: indented below it)."""
    if "end_time" in s:
        return float(s["end_time"])
    try:
        with open(os.path.join(path, "scene.yaml")) as f:
            text = f.read()
    except OSError:
        return None
    m = re.search(r"^# --end-time (\S+)$", text, re.M) or \
        re.search(r"^time:\n(?:[ \t]+.*\n)*?[ \t]+end:[ \t]*([-+0-9.eE]+)[ \t]*$", text, re.M)
    return float(m.group(1)) if m else None


def to_finish(path, s):
    """Wall seconds left to end_time at this segment's pace: the mean dt of its last 100 steps
    and its wall seconds per step (same ranks and load; dt may still shrink). None if unknown."""
    t_end, n, wall = end_time(path, s), s.get("steps_this_run"), s.get("wall_seconds")
    if t_end is None or not n or not wall:
        return None
    try:
        dts = [float(x) for x in series.timeseries(path).get("dt", [])[-100:]]
    except (OSError, ValueError):
        return None
    if not dts or min(dts) <= 0:
        return None
    return max(0.0, t_end - s["simulated_time"]) / (sum(dts) / len(dts)) * wall / n


def revisions(s):
    """The builds that ran the run's segments, in order, repeats dropped ("?" for segments
    from before summary.json recorded them, "" if it records none)."""
    out = []
    for seg in s.get("segment_history", []):
        r = seg.get("revision") or "?"
        if not out or out[-1] != r:
            out.append(r)
    return " ".join(out)


def end(ledger, rid, path, code, since):
    values = {"state": EXIT_STATE.get(code, "failed")}
    s = summary(path)
    # A summary older than this run's start is an earlier segment's (this one wrote none).
    if s is not None and os.path.getmtime(os.path.join(path, "summary.json")) >= since:
        wall = s.get("wall_seconds_total")
        values.update(t_reached="%.6g" % s["simulated_time"], steps=str(s["steps"]),
                      wall_s="%.1f" % (s["wall_seconds"] if wall is None else wall))
        # Only a run that can go on has a cost to finish (a blow-up has none).
        left = {"finished": 0.0, "wall_limit": None, "stopped": None}.get(values["state"], "")
        if left is None:
            left = to_finish(path, s)
        values["to_finish_s"] = "" if left in (None, "") else "%.0f" % left
        values["revisions"] = revisions(s)
    update(ledger, rid, values)


def checkpoint_reached(path):
    """(step, t) of the checkpoint `latest` names, t from timeseries.csv; None if none."""
    try:
        with open(os.path.join(path, "latest")) as f:
            step = int(re.search(r"(\d+)", f.read()).group(1))
        with open(os.path.join(path, "timeseries.csv"), newline="") as f:
            t = next((r["t"] for r in csv.DictReader(f) if r.get("step") == str(step)), None)
    except (OSError, AttributeError, ValueError):
        return None
    return None if t is None else (step, float(t))


def progress(ledger, out):
    """Records how far each running run has a checkpoint, so that a ledger committed while it
    runs says what a later job can continue from. Returns the run ids updated."""
    with open(ledger, newline="") as f:
        ids = [r["run_id"] for r in csv.DictReader(f) if r.get("state") == "running"]
    done = []
    for rid in ids:
        got = checkpoint_reached(os.path.join(out, rid))
        if got is not None:
            update(ledger, rid, {"steps": str(got[0]), "t_reached": "%.6g" % got[1]})
            done.append(rid)
    return done


def recorded(ledger, rid):
    """The ledger's word on a run: what a fresh machine (no outputs) knows of it."""
    if not os.path.exists(ledger):
        return ""
    with open(ledger, newline="") as f:
        row = next((r for r in csv.DictReader(f) if r.get("run_id") == rid), None)
    return "" if row is None else row.get("state", "")


def rows_by_id(path):
    """A CSV keyed by run id (a ledger or a results.csv); {} when the file is missing."""
    if not os.path.exists(path):
        return {}
    with open(path, newline="") as f:
        return {r["run_id"]: r for r in csv.DictReader(f)}


def unfinished(row):
    """A ledger row of a run that has not finished, in words: how far it got and what
    finishing would cost (the cases' table.py quote it)."""
    if not row.get("t_reached"):
        return "*not finished*: %s, no checkpoint yet" % row["state"]
    # A first segment still running has no wall time recorded yet: say nothing of it.
    return "*not finished*: %s at t = %s s (%s steps%s)%s" % (
        row["state"], row["t_reached"], row["steps"], ", %s s" % row["wall_s"] if row.get("wall_s") else "",
        "; to finish ~%s s" % row["to_finish_s"] if row.get("to_finish_s") else "")


def not_run(results, rid, t_end):
    """A run of the set not begun, in words: for a run on the exact projection whose twin on
    the approximate one (the same id without "+exact") reached t_end, what that one took, the
    nearest measure of what this one will (issue 22 item 5; the exact step costs about what
    the approximate one did, perf/README.md)."""
    twin = results.get(rid.replace("+exact", "")) if "+exact" in rid else None
    try:
        reached = twin is not None and abs(float(twin["t_end"]) - t_end) <= 1e-6 * t_end and int(twin["steps"]) > 0
    except (KeyError, ValueError):
        reached = False
    if not reached:
        return "*not run*"
    return "*not run*; on the approximate projection %s steps, %s s on %s rank(s)" % (
        twin["steps"], twin.get("wall_s", "?"), twin.get("ranks", "?"))


def table(ledger, ids):
    with open(ledger, newline="") as f:
        rows = [r for r in csv.DictReader(f) if not ids or r.get("run_id") in ids]
    out = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    out += ["| " + " | ".join(r.get(c, "") for c in COLUMNS) + " |" for r in rows]
    return "\n".join(out)
