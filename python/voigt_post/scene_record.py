"""What a run was: the scene record Voigt writes into its output directory (scene.yaml at the
start, scene_segment<N>.yaml when a restart changed the scene), with every --set applied.
Runs from before 2026-12-02 have none. Needs Debian's python3-yaml when there is a record.

The case scripts read a run's parameters here (domain, materials, gravity, shapes) rather than
keeping copies of the scene's numbers: scene(), or scene_or() where a script must also work on
runs without a record (it then reads the case's scene file and says so), and the accessors
spacing(), extent(), material() and level_set()."""
import glob
import os
import re
import sys

# The falling block's cylinder in every run made before runs recorded their scene (x, y, r).
LEGACY_CYLINDER = (0.045, 0.0375, 0.01)


def record_path(outdir):
    """The newest record of the run (its last changed segment), or None."""
    seg = glob.glob(os.path.join(outdir, "scene_segment*.yaml"))
    if seg:
        return max(seg, key=lambda p: int(re.search(r"scene_segment(\d+)\.yaml$", p).group(1)))
    path = os.path.join(outdir, "scene.yaml")
    return path if os.path.exists(path) else None


def scene(outdir):
    """The run's scene as a dict, or None when the run has no record (OUTDIR: a folder or a
    digest, which keeps the newest record)."""
    from . import digest
    if digest.is_digest(outdir):
        import yaml
        data = digest.text(outdir, "scene.yaml")
        return None if data is None else yaml.safe_load(data)
    path = record_path(outdir)
    if path is None:
        return None
    import yaml
    with open(path) as f:
        return yaml.safe_load(f)


def cylinder(outdir, default=LEGACY_CYLINDER):
    """(x, y, r) of the run's first cylinder obstacle (axis z). Without a record: `default`
    (the 4.5 cm cylinder of the older runs), with a warning on stderr."""
    sc = scene(outdir)
    if sc is None:
        print("%s: no scene.yaml (run before 2026-12-02): assuming the cylinder at x, y, r = %s m; "
              "pass it explicitly if that run had another" % (outdir, default), file=sys.stderr)
        return default
    for ob in sc.get("obstacles") or []:
        if ob.get("type") == "cylinder" and ob.get("axis", "z") == "z":
            c = ob["center"]
            return (float(c[0]), float(c[1]), float(ob["radius"]))
    raise ValueError("%s: the scene record has no cylinder along z" % outdir)


def load(path):
    """A scene file (or a record) as a dict."""
    import yaml
    with open(path) as f:
        return yaml.safe_load(f)


def require(outdir, who):
    """The run's scene, or the end of the program WHO when the run has no record."""
    sc = scene(outdir)
    if sc is None:
        raise SystemExit("%s: %s has no scene record (scene.yaml; runs before 2026-12-02)" % (who, outdir))
    return sc


def scene_or(outdir, fallback, who):
    """The run's scene; without a record the scene file FALLBACK (the case's scene, which the
    run is assumed to have used), with a note on stderr from WHO."""
    sc = scene(outdir)
    if sc is not None:
        return sc
    print("%s: %s has no scene record: its parameters from %s" % (who, outdir, fallback), file=sys.stderr)
    return load(fallback)


def extent(sc):
    """(lo, hi) of the scene's domain, each three floats."""
    d = sc["domain"]
    return [float(v) for v in d["lo"]], [float(v) for v in d["hi"]]


def spacing(sc):
    """The cell size (hx, hy, hz) of the scene's grid."""
    lo, hi = extent(sc)
    return tuple((hi[k] - lo[k]) / sc["domain"]["cells"][k] for k in range(3))


def material(sc, name=None):
    """The material NAME (default: the scene's fluid, where no level set is positive)."""
    return sc["materials"][sc["fluid"] if name is None else name]


def level_set(sc, name=None):
    """The level set NAME of `level_sets`, or the scene's single `level_set` (name None)."""
    if name is None and "level_set" in sc:
        return sc["level_set"]
    for ls in sc.get("level_sets") or []:
        if name is None or ls.get("name") == name:
            return ls
    raise KeyError("the scene has no level set %s" % (name or ""))

