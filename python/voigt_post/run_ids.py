"""The run ids of the studies (cases/study.sh, cases/<case>/runs.csv and results.csv): the grid,
the fluid-side model tagged with the volume correction, projection and defaults a run used,
and the id mu<MODULUS>_<MODEL+TAGS>_<GRID>; durations as the run scripts' --wall-limit takes
them. Standard library only; cases/runs.py is their command line."""
import re


def grid_of(scene, sets):
    """Cells as "NxNyNz": the last domain.cells of the --set values, else the scene's."""
    for s in reversed(sets):
        if s.startswith("domain.cells="):
            return "x".join(re.findall(r"\d+", s.split("=", 1)[1]))
    with open(scene) as f:
        m = re.search(r"^\s+cells:\s*\[([^\]]*)\]", f.read(), re.M)
    return "x".join(re.findall(r"\d+", m.group(1)))


def projection_of(scene, sets):
    """The run's projection operator: the last projection.operator of the --set values, else the
    scene's (its `projection:` section), else Voigt's default, exact."""
    for s in reversed(sets):
        if s.startswith("projection.operator="):
            return s.split("=", 1)[1].strip()
    with open(scene) as f:
        sec = re.search(r"^projection:[^\n]*\n((?:[ \t]+.*\n|[ \t]*\n)*)", f.read(), re.M)
    m = re.search(r"^\s+operator:\s*(\w+)", sec.group(1), re.M) if sec else None
    return m.group(1) if m else "exact"


def tagged_model(model, sets, scene=None):
    """The fluid-side model with the level set's volume correction: "integrate+global" (the
    default since 2026-12-03) or "integrate+none" (rows from before hold the bare name), and
    "+exact" when the run projects with the exact operator (issue 19; every paper-scene run
    before 2026-12-05 used the approximate one, and their ids carry no projection tag), then
    "+balanced" and "+settled" (issue 50) and "+surface" (issue 53)."""
    corr = "global"
    for s in sets:
        if s.startswith("level_set.volume_correction="):
            corr = s.split("=", 1)[1].strip()
    tag = "+exact" if scene and projection_of(scene, sets) == "exact" else ""
    # "+balanced": balanced gravity and rho^{n+1} in the momentum stage (issue 50, 2026-12-06),
    # the default with the exact operator; earlier exact runs carry "+exact" alone.
    if tag and not any(s.strip() == "projection.hydrostatic=none" for s in sets):
        tag += "+balanced"
    # "+settled": reinit.zone_tolerance > 0, the default since 2026-12-06 (issue 50): settled
    # smoothing-zone cells keep their advected values. Earlier runs carry no tag.
    if not any(s.strip() in ("reinit.zone_tolerance=0", "reinit.zone_tolerance=0.0") for s in sets):
        tag += "+settled"
    # "+surface": level_set.surface_velocity: solid, the default since 2026-12-08 (issue 53): the
    # solid's surface moves with the solid's velocity. Earlier runs carry no tag.
    if not any(s.strip() == "level_set.surface_velocity=flow" for s in sets):
        tag += "+surface"
    return "%s+%s%s" % (model, corr, tag)


def run_id(modulus, model, grid):
    n = grid.split("x")
    return "mu%s_%s_%s" % (modulus, model, n[0] if len(set(n)) == 1 else grid)


def seconds(text):
    if ":" in text:
        parts = text.split(":")
        if len(parts) > 3 or not all(p.isdigit() for p in parts):
            raise ValueError(text)
        total = 0.0
        for p in parts:
            total = total * 60 + int(p)
    else:
        pieces = re.fullmatch(r"(?:\d+(?:\.\d*)?[dhms]?)+", text) and re.findall(r"(\d+(?:\.\d*)?)([dhms]?)", text)
        if not pieces:
            raise ValueError(text)
        scale = {"d": 86400, "h": 3600, "m": 60, "s": 1, "": 1}
        total = sum(float(v) * scale[u] for v, u in pieces)
    if not total > 0:
        raise ValueError(text)
    return total
