"""What a run was: the scene record Voigt writes into its output directory (scene.yaml at the
start, scene_segment<N>.yaml when a restart changed the scene), with every --set applied.
Runs from before 2026-12-02 have none. Needs Debian's python3-yaml when there is a record."""
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
