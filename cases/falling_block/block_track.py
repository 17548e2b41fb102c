#!/usr/bin/python3
"""Block diagnostics from a falling_block run's HDF5 output (Python 3 + numpy, h5py or h5dump:
python/voigt_post/fields.py; python3-yaml for the run's scene record, unless --cylinder is given).

An independent check of the solver's `solid_body` effect (timeseries.csv, every step): at every
output time the same measures from the written fields, with the same definitions
(src/effects/solid_body.cpp): weights H(psi) of Eq. (4), centroid, mean velocity, orientation of
the thin axis, bending (largest deviation of the mid-surface from its best-fit plane), gaps
min(d(x) - psi(x)) over -2 h < psi < h to the cylinder and to the base; then, from
probe_centre.csv (every 0.005 s), the velocity at the block's centre.

    cases/falling_block/block_track.py OUTPUT_DIR [--cylinder X Y R] [--sharp] > track.csv
    cases/falling_block/block_track.py OUTPUT_DIR --probes > probes.csv   # every 0.005 s

--sharp: the earlier stand-in (cells with psi > 0 counted whole, gaps from cell centres minus
h/2; positions good to about h/2).
"""
import math
import sys

from voigt_post import fields, series
from voigt_post.formulas import heaviside
from voigt_post.scene_record import cylinder
from voigt_post.xdmf import frames


def read_flat(path, name):
    """A field as a flat list of floats in the file's (z, y, x[, component]) order."""
    return fields.read(path, name).ravel().tolist()


def jacobi_eig(a):
    """Eigenvalues and eigenvectors (columns) of a symmetric 3x3 matrix."""
    a = [row[:] for row in a]
    v = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    for _ in range(50):
        off = sum(a[i][j] ** 2 for i in range(3) for j in range(3) if i != j)
        if off < 1e-30:
            break
        for p in range(3):
            for q in range(p + 1, 3):
                if abs(a[p][q]) < 1e-300:
                    continue
                th = 0.5 * math.atan2(2 * a[p][q], a[q][q] - a[p][p])
                c, s = math.cos(th), math.sin(th)
                for k in range(3):
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(3):
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(3):
                    vkp, vkq = v[k][p], v[k][q]
                    v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    return [a[i][i] for i in range(3)], v


def smoothing_cells(outdir):
    """kappa in cells (summary.json), 2 for a run without one."""
    return series.summary(outdir, {}).get("level_set", {}).get("smoothing_cells", 2.0)


def plane_deviation(mid):
    """Largest |s - (p0 + p1 a + p2 b)| over the points (a, b, s), least-squares plane."""
    if len(mid) < 3:
        return 0.0
    A = [[0.0] * 3 for _ in range(3)]
    rhs = [0.0] * 3
    for a, b, w in mid:
        row = (1.0, a, b)
        for i in range(3):
            rhs[i] += row[i] * w
            for j in range(3):
                A[i][j] += row[i] * row[j]

    def det(M):
        return (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
                - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
    D = det(A)
    if D == 0:
        return 0.0
    coef = []
    for col in range(3):   # Cramer's rule
        M = [row[:] for row in A]
        for i in range(3):
            M[i][col] = rhs[i]
        coef.append(det(M) / D)
    return max(abs(w - coef[0] - coef[1] * a - coef[2] * b) for a, b, w in mid)


def analyse(outdir, cyl, sharp):
    """Per output time, the solid_body effect's measures (src/effects/solid_body.cpp): weights
    H(psi) (or 1 where psi > 0 with --sharp), gaps min(d(x) - psi(x)) over -2 h < psi < h."""
    cx, cy, r = cyl
    kcells = smoothing_cells(outdir)
    print("t,volume,cx,cy,cz,vx,vy,vz,tilt_deg,angle_z_deg,bending,gap_cylinder,gap_base,"
          "contact_cylinder,contact_base")
    for t, path, (nx, ny, nz), (ox, oy, oz), (hx, hy, hz) in frames(outdir):
        h = min(hx, hy, hz)
        kappa = kcells * h
        psi = read_flat(path, "psi")
        vel = read_flat(path, "velocity")
        pts, vs, ws = [], [], []
        gcyl, gbase = float("inf"), float("inf")
        for k in range(nz):
            for j in range(ny):
                for i in range(nx):
                    ps = psi[(k * ny + j) * nx + i]
                    p = (ox + (i + 0.5) * hx, oy + (j + 0.5) * hy, oz + (k + 0.5) * hz)
                    if sharp and ps > 0:
                        gcyl = min(gcyl, math.hypot(p[0] - cx, p[1] - cy) - r - 0.5 * hx)
                        gbase = min(gbase, p[1] - oy - 0.5 * hy)
                    elif not sharp and -2 * h < ps < h:
                        dist = ps
                        dc = math.hypot(p[0] - cx, p[1] - cy) - r
                        if dc >= 0 or ps > 0:   # fluid cells inside the cylinder are skipped
                            gcyl = min(gcyl, dc - dist)
                            gbase = min(gbase, p[1] - oy - dist)
                    w = (1.0 if ps > 0 else 0.0) if sharp else heaviside(ps, kappa)
                    if w <= 0:
                        continue
                    pts.append(p)
                    ws.append(w)
                    v = [0.0, 0.0, 0.0]
                    for dk in (0, 1):
                        for dj in (0, 1):
                            for di in (0, 1):
                                b = (((k + dk) * (ny + 1) + j + dj) * (nx + 1) + i + di) * 3
                                for c in range(3):
                                    v[c] += 0.125 * vel[b + c]
                    vs.append(v)
        W = sum(ws)
        if W == 0:
            print("%g,0" % t)
            continue
        c = [sum(w * p[d] for w, p in zip(ws, pts)) / W for d in range(3)]
        u = [sum(w * v[d] for w, v in zip(ws, vs)) / W for d in range(3)]
        cov = [[sum(w * (p[a] - c[a]) * (p[b] - c[b]) for w, p in zip(ws, pts)) / W for b in range(3)]
               for a in range(3)]
        ev, vec = jacobi_eig(cov)
        order = sorted(range(3), key=lambda q: ev[q])
        nrm = [vec[d][order[0]] for d in range(3)]       # thin axis
        e1 = [vec[d][order[2]] for d in range(3)]
        e2 = [vec[d][order[1]] for d in range(3)]
        if nrm[1] < 0:
            nrm = [-q for q in nrm]
        tilt = math.degrees(math.acos(min(1.0, abs(nrm[1]))))
        ang = math.degrees(math.atan2(-nrm[0], nrm[1]))   # rotation of the thin axis about z
        # Mid-surface: weighted mean (a, b, s) in columns h apart over the block's plane.
        bins = {}
        for w, p in zip(ws, pts):
            d = [p[q] - c[q] for q in range(3)]
            a = sum(d[q] * e1[q] for q in range(3))
            b = sum(d[q] * e2[q] for q in range(3))
            s_ = sum(d[q] * nrm[q] for q in range(3))
            if sharp:   # the earlier stand-in: nearest column
                shares = [((math.floor(a / h + 0.5), math.floor(b / h + 0.5)), w)]
            else:       # bilinear share to the 4 nearest column centres, as the solver
                fa, fb = a / h, b / h
                ia, ib = math.floor(fa), math.floor(fb)
                shares = [((ia + da, ib + db), w * (fa - ia if da else 1 - (fa - ia)) * (fb - ib if db else 1 - (fb - ib)))
                          for db in (0, 1) for da in (0, 1)]
            for key, kw in shares:
                sb = bins.setdefault(key, [0.0, 0.0, 0.0, 0.0])
                sb[0] += kw * a; sb[1] += kw * b; sb[2] += kw * s_; sb[3] += kw
        lim = 2 if sharp else 1   # cells (sharp, as before) or one cell's worth of H
        mid = [(sb[0] / sb[3], sb[1] / sb[3], sb[2] / sb[3]) for sb in bins.values() if sb[3] >= lim]
        bend = plane_deviation(mid)
        vol = W * hx * hy * hz
        print("%.6g,%.6g,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f,%.3f,%.3f,%.6f,%.6f,%.6f,%d,%d" % (
            t, vol, c[0], c[1], c[2], u[0], u[1], u[2], tilt, ang, bend, gcyl, gbase,
            gcyl < h, gbase < h))


def probes(outdir):
    """Every probe sample: underside and top (psi = 0 crossings) on the three vertical lines,
    and the velocity at the deepest point (largest psi) of the centre line."""
    cols = {name: series.probe(outdir, name) for name in ("left", "centre", "right")}
    print("t,bottom_left,top_left,bottom_centre,top_centre,bottom_right,top_right,vx_centre,vy_centre")
    for t in sorted(cols["centre"]):
        out = [t]
        for name in ("left", "centre", "right"):
            rs = sorted(cols[name].get(t, []), key=lambda r: r["y"])
            cross = [rs[i]["y"] + (rs[i + 1]["y"] - rs[i]["y"]) * rs[i]["psi"] / (rs[i]["psi"] - rs[i + 1]["psi"])
                     for i in range(len(rs) - 1) if (rs[i]["psi"] > 0) != (rs[i + 1]["psi"] > 0)]
            out += [cross[0], cross[-1]] if cross else [float("nan")] * 2
        rs = cols["centre"][t]
        deep = max(rs, key=lambda r: r["psi"])
        out += [deep["velocity_x"], deep["velocity_y"]] if deep["psi"] > 0 else [float("nan")] * 2
        print(",".join("%.5g" % v for v in out))


if __name__ == "__main__":
    args = sys.argv[1:]
    if not args or args[0].startswith("-"):
        sys.exit(__doc__)
    if "--probes" in args:
        probes(args[0])
    else:
        if "--cylinder" in args:
            i = args.index("--cylinder")
            cyl = tuple(float(v) for v in args[i + 1:i + 4])
        else:
            cyl = cylinder(args[0])   # the run's cylinder (axis z), from its scene record
        analyse(args[0], cyl, "--sharp" in args)
