"""What a run was: its DIR/scene.yaml, which Voigt writes at the start of every run (the scene
with all --set overrides applied). Runs from before 2026-12-02 have none."""
import os

# The falling block's cylinder in every run made before runs recorded their scene (x, y, r).
LEGACY_CYLINDER = (0.045, 0.0375, 0.01)


def scene(outdir):
    """The run's scene as a dict, or None when the run has no scene.yaml."""
    path = os.path.join(outdir, "scene.yaml")
    if not os.path.exists(path):
        return None
    import yaml  # Debian python3-yaml; only needed when there is a record
    with open(path) as f:
        return yaml.safe_load(f)


def cylinder(outdir, default=LEGACY_CYLINDER):
    """(x, y, r) of the run's first obstacle of type cylinder (axis z); `default` without a record."""
    sc = scene(outdir)
    if sc is None:
        return default
    for ob in sc.get("obstacles") or []:
        if ob.get("type") == "cylinder":
            c = ob["center"]
            return (float(c[0]), float(c[1]), float(ob["radius"]))
    raise ValueError("%s/scene.yaml has no cylinder obstacle" % outdir)
