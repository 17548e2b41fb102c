"""The level set's surface psi = 0 coloured by a field, like the paper's Figs. 1-2: one row per
run, one column per output time, the obstacles of the run's scene record in grey, headless to
PNG with VTK (Debian python3-vtk9, python3-h5py: fields.py; VTK needs an X server, so without DISPLAY the
command re-runs itself under xvfb-run).

    scripts/picture output/demo -o output/demo.png [--times 0.1 0.2 0.3] [--field log10_S2]
    scripts/picture --run output/fb_1000 "mu_S = 1000 Pa" --run output/fb_5000 "mu_S = 5000 Pa" -o b.png

Colour: `--field` (default log10_S2 when the output has it, else none) sampled one cell on the
psi > 0 side of the surface (along grad psi): for a solid phase the band's fluid side can carry
stress integrated from the surrounding flow (cases/falling_block/NOTEBOOK.md), which would
otherwise colour the surface. The frame nearest each requested time is drawn. A run may be
its digest (digest.py), which keeps psi and the colour around the surface at a few times.
"""
import argparse
import os
import shutil
import subprocess
import sys

from . import digest, fields
from .scene_record import scene
from .xdmf import frames

VIEW = (0.6, 0.9, 2.6)       # camera direction from the domain's centre: front, a little above, right


def _headless():
    """Re-runs this command under xvfb-run when there is no X display (VTK's off-screen
    rendering in Debian's build still opens one)."""
    if os.environ.get("DISPLAY") or os.environ.get("VOIGT_RENDER_CHILD"):
        return
    if not shutil.which("xvfb-run"):
        sys.exit("picture: no DISPLAY and no xvfb-run (Debian: apt-get install xvfb; scripts/setup --figures)")
    env = dict(os.environ, VOIGT_RENDER_CHILD="1")
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                                      env.get("PYTHONPATH")]))
    as_module = os.path.abspath(sys.argv[0]) == os.path.abspath(__file__)   # python -m voigt_post.picture
    cmd = [sys.executable] + (["-m", "voigt_post.picture"] if as_module else [sys.argv[0]])
    sys.exit(subprocess.call(["xvfb-run", "-a", "-s", "-screen 0 1920x1080x24"] + cmd + sys.argv[1:], env=env))


def _arrays(f, field):
    """(psi, colour or None, the arrays' origin) of an output: a fields.xdmf frame, or a digest's
    (digest.py: cropped around the surface, float32)."""
    if isinstance(f, digest.Frame):
        return f.psi, (f.colour if field and field == f.field else None), f.crop_origin
    return fields.read(f.path, "psi"), (fields.read(f.path, field) if field else None), f.origin


def _frames(d):
    return digest.frames(d) if digest.is_digest(d) else frames(d)


def _has_field(d, field):
    if digest.is_digest(d):
        return any(f.field == field for f in digest.frames(d))
    return field in fields.names(frames(d)[0].path)


def surface(psi, col, orig, sp, field):
    """psi = 0 as smooth-shaded polydata; with `field` (its array col), its value one cell on the
    psi > 0 side. Arrays in (z, y, x) order, orig the centre-of-cell grid's lower corner."""
    import numpy as np
    import vtk
    from vtk.util import numpy_support as ns
    gz, gy, gx = np.gradient(psi, sp[2], sp[1], sp[0])
    arrays = {"psi": psi, "grad": np.stack([gx, gy, gz], axis=-1)}
    if col is not None:
        arrays["colour"] = col if col.ndim == 3 else np.linalg.norm(col, axis=-1)   # vectors: magnitude
    nz, ny, nx = psi.shape
    im = vtk.vtkImageData()                 # cell-centred fields as the points of an image
    im.SetDimensions(nx, ny, nz)
    im.SetOrigin(*(o + 0.5 * s for o, s in zip(orig, sp)))
    im.SetSpacing(*sp)
    for name, a in arrays.items():
        v = ns.numpy_to_vtk(np.ascontiguousarray(a.reshape(-1, *a.shape[3:])), deep=True)
        v.SetName(name)
        im.GetPointData().AddArray(v)
    im.GetPointData().SetActiveScalars("psi")
    cf = vtk.vtkContourFilter()
    cf.SetInputData(im)
    cf.SetValue(0, 0.0)
    cf.ComputeNormalsOff()
    cf.ComputeScalarsOff()
    cf.Update()
    surf = cf.GetOutput()
    if surf.GetNumberOfPoints() and col is not None:
        pr = vtk.vtkProbeFilter()           # grad psi at the surface points
        pr.SetInputData(surf)
        pr.SetSourceData(im)
        pr.Update()
        pts = ns.vtk_to_numpy(surf.GetPoints().GetData())
        g = ns.vtk_to_numpy(pr.GetOutput().GetPointData().GetArray("grad"))
        n = g / np.maximum(np.linalg.norm(g, axis=1), 1e-30)[:, None]
        inner = vtk.vtkPolyData()
        ip = vtk.vtkPoints()
        ip.SetData(ns.numpy_to_vtk(pts + min(sp) * n, deep=True))
        inner.SetPoints(ip)
        pr2 = vtk.vtkProbeFilter()
        pr2.SetInputData(inner)
        pr2.SetSourceData(im)
        pr2.Update()
        arr = ns.numpy_to_vtk(ns.vtk_to_numpy(pr2.GetOutput().GetPointData().GetArray("colour")).copy(), deep=True)
        arr.SetName(field)
        surf.GetPointData().SetScalars(arr)
    nm = vtk.vtkPolyDataNormals()
    nm.SetInputData(surf)
    nm.Update()
    return nm.GetOutput()


def obstacle_sources(sc, lo, hi):
    """VTK sources for the obstacles of a scene record (cylinder, box, sphere; src/scene/load.cpp)."""
    import vtk
    out = []
    for ob in (sc or {}).get("obstacles") or []:
        kind = ob.get("type")
        if kind == "cylinder":
            ax = "xyz".index(ob.get("axis", "z"))
            c = [float(v) for v in ob["center"]]
            src = vtk.vtkCylinderSource()   # along y; turned to the axis below
            src.SetRadius(float(ob["radius"]))
            src.SetHeight(hi[ax] - lo[ax])
            src.SetResolution(48)
            c[ax] = 0.5 * (lo[ax] + hi[ax])
            rot = {0: (0, 0, 90), 1: (0, 0, 0), 2: (90, 0, 0)}[ax]
            out.append((src, c, rot))
        elif kind == "box":
            src = vtk.vtkCubeSource()
            b = [float(v) for v in ob["lo"]], [float(v) for v in ob["hi"]]
            src.SetBounds(b[0][0], b[1][0], b[0][1], b[1][1], b[0][2], b[1][2])
            out.append((src, (0, 0, 0), (0, 0, 0)))
        elif kind == "sphere":
            src = vtk.vtkSphereSource()
            src.SetRadius(float(ob["radius"]))
            src.SetThetaResolution(40)
            src.SetPhiResolution(24)
            out.append((src, [float(v) for v in ob["center"]], (0, 0, 0)))
    return out


def _text(ren, s, x, y, size=13, bold=False):
    import vtk
    a = vtk.vtkTextActor()
    a.SetInput(s)
    a.GetTextProperty().SetFontSize(size)
    a.GetTextProperty().SetBold(bold)
    a.GetTextProperty().SetColor(0, 0, 0)
    a.SetDisplayPosition(x, y)
    ren.AddActor2D(a)


def _actor(src_or_data, colour=None, table=None, rng=None):
    import vtk
    m = vtk.vtkPolyDataMapper()
    if isinstance(src_or_data, vtk.vtkPolyData):
        m.SetInputData(src_or_data)
    else:
        m.SetInputConnection(src_or_data.GetOutputPort())
    if table is not None:
        m.SetLookupTable(table)
        m.SetScalarRange(*rng)
    else:
        m.ScalarVisibilityOff()
    a = vtk.vtkActor()
    a.SetMapper(m)
    if colour is not None:
        a.GetProperty().SetColor(*colour)
    return a


def draw(runs, times, output, field=None, title="", rng=None, panel=(260, 230), legacy_obstacles=None):
    """Renders runs [(dir, label)] x times to `output` (PNG); returns (width, height, range).
    `field` None: log10_S2 when the first frame has it, else a plain surface. Obstacles come
    from each run's scene record; `legacy_obstacles` (a scene-like dict) for runs without one."""
    import numpy as np
    import vtk
    from vtk.util import numpy_support as ns
    if field is None:
        field = "log10_S2" if _has_field(runs[0][0], "log10_S2") else ""
    rows, cols = len(runs), len(times)
    pw, ph = panel
    top, bar = 28, (60 if field else 0)
    W, H = pw * cols, ph * rows + top + bar
    panels = []
    for d, label in runs:
        fr = _frames(d)
        sc = scene(d) or legacy_obstacles
        for c, t in enumerate(times):
            f = min(fr, key=lambda g: abs(g.t - t))
            hi = [o + s * n for o, s, n in zip(f.origin, f.spacing, f.cells)]
            psi, col, orig = _arrays(f, field)
            panels.append((len(panels) // cols, c, label, f.t, surface(psi, col, orig, f.spacing, field),
                           f.origin, hi, obstacle_sources(sc, f.origin, hi)))
    if field and rng is None:
        vals = [ns.vtk_to_numpy(p[4].GetPointData().GetScalars()) for p in panels
                if p[4].GetNumberOfPoints() and p[4].GetPointData().GetScalars() is not None]
        vals = np.concatenate(vals) if vals else np.zeros(0)
        vals = vals[np.isfinite(vals)]
        rng = (np.percentile(vals, 2), np.percentile(vals, 98)) if vals.size else (0.0, 1.0)
    table = None
    if field:
        table = vtk.vtkLookupTable()
        table.SetRange(*rng)
        table.SetHueRange(0.667, 0.0)       # blue (low) to red (high), as the paper's colour map
        table.Build()
    rw = vtk.vtkRenderWindow()
    rw.SetOffScreenRendering(1)
    rw.SetSize(W, H)
    rw.SetNumberOfLayers(2)                 # 0: white page and panels; 1: labels and colour bar
    page = vtk.vtkRenderer()
    page.SetBackground(1, 1, 1)
    rw.AddRenderer(page)
    over = vtk.vtkRenderer()
    over.SetLayer(1)
    for r, c, label, t, surf, lo, hi, obs in panels:
        ren = vtk.vtkRenderer()
        ren.SetBackground(1, 1, 1)
        x0, y1 = c * pw / W, 1 - (top + r * ph) / H
        ren.SetViewport(x0, y1 - ph / H, x0 + pw / W, y1)
        ren.AddActor(_actor(surf, None if field else (0.55, 0.7, 0.95), table, rng))
        box = vtk.vtkOutlineSource()
        box.SetBounds(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2])
        ren.AddActor(_actor(box, (0.4, 0.4, 0.4)))
        for src, pos, rot in obs:
            a = _actor(src, (0.75, 0.75, 0.75))
            a.RotateX(rot[0])
            a.RotateZ(rot[2])
            a.SetPosition(*pos)
            a.GetProperty().SetAmbient(0.35)
            ren.AddActor(a)
        cam = ren.GetActiveCamera()
        ctr = [0.5 * (a + b) for a, b in zip(lo, hi)]
        cam.SetFocalPoint(*ctr)
        cam.SetPosition(*(x + v for x, v in zip(ctr, VIEW)))
        cam.SetViewUp(0, 1, 0)
        ren.ResetCamera(lo[0], hi[0], lo[1], hi[1], lo[2], hi[2])
        cam.Zoom(1.15)
        rw.AddRenderer(ren)
        _text(over, "%s, t = %.3g s" % (label, t) if label else "t = %.3g s" % t, c * pw + 6, H - top - r * ph - 18, 12)
    rw.AddRenderer(over)
    if title:
        _text(over, title, 8, H - 22, 15, True)
    if field:
        sb = vtk.vtkScalarBarActor()
        sb.SetLookupTable(table)
        sb.SetTitle("%s, 1 cell inside" % field)
        sb.SetOrientationToHorizontal()
        sb.SetNumberOfLabels(5)
        for p in (sb.GetTitleTextProperty(), sb.GetLabelTextProperty()):
            p.SetColor(0, 0, 0)
            p.SetFontSize(12)
        sb.SetPosition(0.2, 0.0)
        sb.SetPosition2(0.6, bar / H * 0.95)
        over.AddActor2D(sb)
    rw.Render()
    w2i = vtk.vtkWindowToImageFilter()
    w2i.SetInput(rw)
    w2i.Update()
    wr = vtk.vtkPNGWriter()
    wr.SetFileName(output)
    wr.SetInputConnection(w2i.GetOutputPort())
    wr.Write()
    return W, H, rng


def main(argv=None, legacy_obstacles=None):
    ap = argparse.ArgumentParser(prog="picture", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="*", help="run output directories (label: none)")
    ap.add_argument("--run", nargs=2, action="append", default=[], metavar=("DIR", "LABEL"))
    ap.add_argument("--times", nargs="+", type=float, default=None,
                    help="default: 4 outputs evenly spread from the first run's first to its last")
    ap.add_argument("--field", default=None, help="colour field (default log10_S2 if written; '' for none)")
    ap.add_argument("--range", nargs=2, type=float, default=None, help="colour range (default: 2-98 percentiles)")
    ap.add_argument("--panel", nargs=2, type=int, default=[260, 230], metavar=("W", "H"))
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args(argv)
    runs = [(d, "") for d in a.dirs] + [tuple(r) for r in a.run]
    if not runs:
        ap.error("no run directory")
    for d, _ in runs:
        if not digest.is_digest(d) and not os.path.exists(os.path.join(d, "fields.xdmf")):
            ap.error("%s: no fields.xdmf (not a Voigt run's output directory or digest?)" % d)
    times = a.times
    if times is None:
        fr = _frames(runs[0][0])
        n = min(4, len(fr))
        times = [fr[round(i * (len(fr) - 1) / max(n - 1, 1))].t for i in range(n)]
    _headless()
    W, H, rng = draw(runs, times, a.output, a.field, a.title, a.range, a.panel, legacy_obstacles)
    print("wrote %s (%d x %d%s)" % (a.output, W, H, ", colour range %.3g-%.3g" % tuple(rng) if rng else ""))


if __name__ == "__main__":
    main()
