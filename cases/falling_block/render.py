#!/usr/bin/python3
"""Renders the falling block's surface psi = 0 shaded by log10(S2), like the paper's Figs. 1-2:
one row per run (mu_S), one column per time, headless to PNG with VTK (Debian python3-vtk9;
an X server is needed, so without DISPLAY the script re-runs itself under xvfb-run).

    cases/falling_block/render.py -o blocks.png --times 0.04 0.08 0.12 \\
        --run output/fb_1000 "mu_S = 1000 Pa" --run output/fb_5000 "mu_S = 5000 Pa" [--title TEXT]

Reads OUTPUT/fields.xdmf and its fields_NNNNNN.h5 (psi, log10_S2 at cell centres; h5py). The
frame nearest each requested time is drawn. S2 is sampled one cell *inside* the surface (along
grad psi): the band's fluid side carries stress integrated from the air flow (README, "What
looked wrong" 1), which would otherwise colour the surface.
"""
import argparse
import os
import shutil
import subprocess
import sys

if not os.environ.get("DISPLAY") and not os.environ.get("VOIGT_RENDER_CHILD"):
    if not shutil.which("xvfb-run"):
        sys.exit("render.py: no DISPLAY and no xvfb-run (Debian: apt-get install xvfb)")
    env = dict(os.environ, VOIGT_RENDER_CHILD="1")
    sys.exit(subprocess.call(["xvfb-run", "-a", "-s", "-screen 0 1920x1080x24", sys.executable] + sys.argv, env=env))

import h5py  # noqa: E402
import numpy as np  # noqa: E402
import vtk  # noqa: E402
from vtk.util import numpy_support as ns  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from scene_record import cylinder  # noqa: E402  (cases/scene_record.py)
from xdmf import frames  # noqa: E402  (cases/xdmf.py)


def image(arrays, orig, sp):
    """vtkImageData at the cell centres holding the given (z, y, x) numpy arrays."""
    nz, ny, nx = next(iter(arrays.values())).shape
    im = vtk.vtkImageData()
    im.SetDimensions(nx, ny, nz)
    im.SetOrigin(*(o + 0.5 * s for o, s in zip(orig, sp)))
    im.SetSpacing(*sp)
    for name, a in arrays.items():
        v = ns.numpy_to_vtk(np.ascontiguousarray(a.reshape(-1, *a.shape[3:])), deep=True)
        v.SetName(name)
        im.GetPointData().AddArray(v)
    return im


def surface(path, orig, sp):
    """psi = 0 as polydata with log10_S2 sampled one cell inside."""
    with h5py.File(path, "r") as f:
        psi = f["psi"][...]
        s2 = f["log10_S2"][...] if "log10_S2" in f else np.zeros_like(psi)
    gz, gy, gx = np.gradient(psi, sp[2], sp[1], sp[0])
    im = image({"psi": psi, "log10_S2": s2, "grad": np.stack([gx, gy, gz], axis=-1)}, orig, sp)
    im.GetPointData().SetActiveScalars("psi")
    cf = vtk.vtkContourFilter()
    cf.SetInputData(im)
    cf.SetValue(0, 0.0)
    cf.ComputeNormalsOff()
    cf.ComputeScalarsOff()
    cf.Update()
    surf = cf.GetOutput()
    if surf.GetNumberOfPoints() == 0:
        return surf
    pr = vtk.vtkProbeFilter()            # grad psi at the surface points
    pr.SetInputData(surf)
    pr.SetSourceData(im)
    pr.Update()
    pts = ns.vtk_to_numpy(surf.GetPoints().GetData())
    g = ns.vtk_to_numpy(pr.GetOutput().GetPointData().GetArray("grad"))
    n = g / np.maximum(np.linalg.norm(g, axis=1), 1e-30)[:, None]   # points into the solid
    inner = vtk.vtkPolyData()
    ip = vtk.vtkPoints()
    ip.SetData(ns.numpy_to_vtk(pts + min(sp) * n, deep=True))
    inner.SetPoints(ip)
    pr2 = vtk.vtkProbeFilter()
    pr2.SetInputData(inner)
    pr2.SetSourceData(im)
    pr2.Update()
    vals = ns.vtk_to_numpy(pr2.GetOutput().GetPointData().GetArray("log10_S2")).copy()
    arr = ns.numpy_to_vtk(vals, deep=True)
    arr.SetName("log10_S2")
    surf.GetPointData().SetScalars(arr)
    nm = vtk.vtkPolyDataNormals()        # smooth shading
    nm.SetInputData(surf)
    nm.Update()
    return nm.GetOutput()


def lut(lo, hi):
    t = vtk.vtkLookupTable()
    t.SetRange(lo, hi)
    t.SetHueRange(0.667, 0.0)            # blue (low) to red (high), as the paper's colour map
    t.Build()
    return t


def text(ren, s, x, y, size=13, bold=False):
    a = vtk.vtkTextActor()
    a.SetInput(s)
    a.GetTextProperty().SetFontSize(size)
    a.GetTextProperty().SetBold(bold)
    a.GetTextProperty().SetColor(0, 0, 0)
    a.SetDisplayPosition(x, y)
    ren.AddActor2D(a)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--run", nargs=2, action="append", metavar=("DIR", "LABEL"), required=True)
    ap.add_argument("--times", nargs="+", type=float, default=[0.04, 0.08, 0.12, 0.24])
    ap.add_argument("--cylinder", nargs=3, type=float, default=None, metavar=("X", "Y", "R"),
                    help="default: each run's scene.yaml (scene_record.py)")
    ap.add_argument("--range", nargs=2, type=float, default=None, help="log10_S2 colour range")
    ap.add_argument("--panel", nargs=2, type=int, default=[260, 230])
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    rows, cols = len(a.run), len(a.times)
    pw, ph = a.panel
    top, bar = 28, 60
    W, H = pw * cols, ph * rows + top + bar
    surfs, dims, cyls = [], [], []
    for d, _ in a.run:
        dims.append(image_dims(d))
        cyls.append(a.cylinder or cylinder(d))
        fr = frames(d)
        row = []
        for t in a.times:
            best = min(fr, key=lambda f: abs(f.t - t))
            row.append((best.t, surface(best.path, best.origin, best.spacing), best.origin, best.spacing))
        surfs.append(row)
    if a.range:
        lo, hi = a.range
    else:
        vals = np.concatenate([ns.vtk_to_numpy(s.GetPointData().GetScalars()) for r in surfs for _, s, _, _ in r
                               if s.GetNumberOfPoints()])
        vals = vals[np.isfinite(vals)]
        lo, hi = (np.percentile(vals, 2), np.percentile(vals, 98)) if vals.size else (0, 1)
    table = lut(lo, hi)
    rw = vtk.vtkRenderWindow()
    rw.SetOffScreenRendering(1)
    rw.SetSize(W, H)
    rw.SetNumberOfLayers(2)              # 0: white page and panels; 1: labels and colour bar
    page = vtk.vtkRenderer()
    page.SetBackground(1, 1, 1)
    rw.AddRenderer(page)
    labels = []
    for r, row in enumerate(surfs):
        for c, (t, s, orig, sp) in enumerate(row):
            ren = vtk.vtkRenderer()
            ren.SetBackground(1, 1, 1)
            x0, y1 = c * pw / W, 1 - (top + r * ph) / H
            ren.SetViewport(x0, y1 - ph / H, x0 + pw / W, y1)
            m = vtk.vtkPolyDataMapper()
            m.SetInputData(s)
            m.SetLookupTable(table)
            m.SetScalarRange(lo, hi)
            act = vtk.vtkActor()
            act.SetMapper(m)
            ren.AddActor(act)
            hi_ = [o + s_ * k for o, s_, k in zip(orig, sp, dims[r])]
            box = vtk.vtkOutlineSource()
            box.SetBounds(orig[0], hi_[0], orig[1], hi_[1], orig[2], hi_[2])
            bm = vtk.vtkPolyDataMapper()
            bm.SetInputConnection(box.GetOutputPort())
            ba = vtk.vtkActor()
            ba.SetMapper(bm)
            ba.GetProperty().SetColor(0.4, 0.4, 0.4)
            ren.AddActor(ba)
            cy = vtk.vtkCylinderSource()     # along y; turned to z
            cy.SetRadius(cyls[r][2])
            cy.SetHeight(hi_[2] - orig[2])
            cy.SetResolution(40)
            cm = vtk.vtkPolyDataMapper()
            cm.SetInputConnection(cy.GetOutputPort())
            ca = vtk.vtkActor()
            ca.SetMapper(cm)
            ca.RotateX(90)
            ca.SetPosition(cyls[r][0], cyls[r][1], 0.5 * (orig[2] + hi_[2]))
            ca.GetProperty().SetColor(0.75, 0.75, 0.75)
            ca.GetProperty().SetAmbient(0.35)
            ren.AddActor(ca)
            cam = ren.GetActiveCamera()
            ctr = [0.5 * (o + e) for o, e in zip(orig, hi_)]
            cam.SetFocalPoint(*ctr)
            cam.SetPosition(ctr[0] + 0.06, ctr[1] + 0.09, ctr[2] + 0.26)   # front, a little above
            cam.SetViewUp(0, 1, 0)
            ren.ResetCameraClippingRange()
            cam.Zoom(1.25)
            labels.append(("%s, t = %.3g s" % (a.run[r][1], t), c * pw + 6, H - top - r * ph - 18))
            rw.AddRenderer(ren)
    over = vtk.vtkRenderer()
    over.SetLayer(1)
    rw.AddRenderer(over)
    if a.title:
        text(over, a.title, 8, H - 22, 15, True)
    for s_, x, y in labels:
        text(over, s_, x, y, 12)
    sb = vtk.vtkScalarBarActor()
    sb.SetLookupTable(table)
    sb.SetTitle("log10 S2 (Pa^2), 1 cell inside")
    sb.SetOrientationToHorizontal()
    sb.SetNumberOfLabels(5)
    sb.GetTitleTextProperty().SetColor(0, 0, 0)
    sb.GetLabelTextProperty().SetColor(0, 0, 0)
    sb.GetTitleTextProperty().SetFontSize(12)
    sb.GetLabelTextProperty().SetFontSize(11)
    sb.SetPosition(0.2, 0.0)
    sb.SetPosition2(0.6, bar / H * 0.95)
    over.AddActor2D(sb)
    rw.Render()
    w2i = vtk.vtkWindowToImageFilter()
    w2i.SetInput(rw)
    w2i.Update()
    wr = vtk.vtkPNGWriter()
    wr.SetFileName(a.output)
    wr.SetInputConnection(w2i.GetOutputPort())
    wr.Write()
    print("wrote %s (%d x %d, log10_S2 range %.3g-%.3g)" % (a.output, W, H, lo, hi))


def image_dims(d):
    """Cells per axis (x, y, z) of a run, from its first frame."""
    return tuple(frames(d)[0].cells)


if __name__ == "__main__":
    main()
