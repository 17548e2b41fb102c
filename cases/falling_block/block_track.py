#!/usr/bin/env python3
"""Block diagnostics from a falling_block run's HDF5 output (Python 3 standard library + h5dump).

Stand-in until the solver writes these itself (README TODO): for every output time, the block
(cells with psi > 0) centroid, mean velocity, orientation of its thin axis, bending (largest
deviation of the mid-surface from its best-fit plane), and the gaps to the cylinder and to the
base; then, from probe_centre.csv (every 0.005 s), the velocity at the block's centre.

    cases/falling_block/block_track.py OUTPUT_DIR [--cylinder X Y R] > track.csv
    cases/falling_block/block_track.py OUTPUT_DIR --probes > probes.csv   # every 0.005 s

Cells are counted as solid where psi > 0 (sharp), so positions are good to about h/2.
"""
import math
import os
import re
import struct
import subprocess
import sys
import tempfile


def read_h5(path, name, count):
    with tempfile.NamedTemporaryFile(suffix=".bin") as f:
        subprocess.run(["h5dump", "-d", name, "-b", "LE", "-o", f.name, path],
                       check=True, stdout=subprocess.DEVNULL)
        data = open(f.name, "rb").read()
    return struct.unpack("<%dd" % count, data)


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


def frames(outdir):
    x = open(os.path.join(outdir, "fields.xdmf")).read()
    for g in re.finditer(r'<Grid Name="(fields_\d+\.h5)" GridType="Uniform">(.*?)</Grid>', x, re.S):
        body = g.group(2)
        t = float(re.search(r'<Time Value="([^"]+)"', body).group(1))
        dims = [int(d) - 1 for d in re.search(r'3DCoRectMesh" Dimensions="([^"]+)"', body).group(1).split()]
        orig = [float(v) for v in re.search(r'Name="Origin"[^>]*>([^<]+)<', body).group(1).split()]
        sp = [float(v) for v in re.search(r'Name="Spacing"[^>]*>([^<]+)<', body).group(1).split()]
        yield t, os.path.join(outdir, g.group(1)), dims, orig, sp   # dims, origin, spacing: z y x


def analyse(outdir, cyl):
    cx, cy, r = cyl
    print("t,solid_cells,volume,cx,cy,cz,vx,vy,vz,tilt_deg,angle_z_deg,bending,gap_cylinder,gap_base,"
          "contact_cylinder,contact_base")
    for t, path, (nz, ny, nx), (oz, oy, ox), (hz, hy, hx) in frames(outdir):
        n = nx * ny * nz
        psi = read_h5(path, "/psi", n)
        vel = read_h5(path, "/velocity", (nx + 1) * (ny + 1) * (nz + 1) * 3)
        pts, vs = [], []
        gcyl, gbase = float("inf"), float("inf")
        for k in range(nz):
            for j in range(ny):
                for i in range(nx):
                    if psi[(k * ny + j) * nx + i] <= 0:
                        continue
                    p = (ox + (i + 0.5) * hx, oy + (j + 0.5) * hy, oz + (k + 0.5) * hz)
                    pts.append(p)
                    v = [0.0, 0.0, 0.0]
                    for dk in (0, 1):
                        for dj in (0, 1):
                            for di in (0, 1):
                                b = (((k + dk) * (ny + 1) + j + dj) * (nx + 1) + i + di) * 3
                                for c in range(3):
                                    v[c] += 0.125 * vel[b + c]
                    vs.append(v)
                    gcyl = min(gcyl, math.hypot(p[0] - cx, p[1] - cy) - r - 0.5 * hx)
                    gbase = min(gbase, p[1] - oy - 0.5 * hy)
        m = len(pts)
        if m == 0:
            print("%g,0" % t)
            continue
        c = [sum(p[d] for p in pts) / m for d in range(3)]
        u = [sum(v[d] for v in vs) / m for d in range(3)]
        cov = [[sum((p[a] - c[a]) * (p[b] - c[b]) for p in pts) / m for b in range(3)] for a in range(3)]
        ev, vec = jacobi_eig(cov)
        order = sorted(range(3), key=lambda q: ev[q])
        nrm = [vec[d][order[0]] for d in range(3)]       # thin axis
        e1 = [vec[d][order[2]] for d in range(3)]
        e2 = [vec[d][order[1]] for d in range(3)]
        if nrm[1] < 0:
            nrm = [-q for q in nrm]
        tilt = math.degrees(math.acos(min(1.0, abs(nrm[1]))))
        ang = math.degrees(math.atan2(-nrm[0], nrm[1]))   # rotation of the thin axis about z
        # Mid-surface: mean normal coordinate in bins of size h over the block's plane.
        bins = {}
        for p in pts:
            d = [p[q] - c[q] for q in range(3)]
            a = sum(d[q] * e1[q] for q in range(3))
            b = sum(d[q] * e2[q] for q in range(3))
            w = sum(d[q] * nrm[q] for q in range(3))
            key = (round(a / hx), round(b / hx))
            s = bins.setdefault(key, [0.0, 0.0, 0.0, 0])
            s[0] += a; s[1] += b; s[2] += w; s[3] += 1
        mid = [(s[0] / s[3], s[1] / s[3], s[2] / s[3]) for s in bins.values() if s[3] >= 2]
        bend = float("nan")
        if len(mid) >= 3:   # least-squares plane w = p0 + p1 a + p2 b
            A = [[0.0] * 3 for _ in range(3)]
            rhs = [0.0] * 3
            for a, b, w in mid:
                row = (1.0, a, b)
                for i in range(3):
                    rhs[i] += row[i] * w
                    for j in range(3):
                        A[i][j] += row[i] * row[j]
            # Cramer's rule
            def det(M):
                return (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
                        - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
                        + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]))
            D = det(A)
            coef = []
            for col in range(3):
                M = [row[:] for row in A]
                for i in range(3):
                    M[i][col] = rhs[i]
                coef.append(det(M) / D)
            bend = max(abs(w - coef[0] - coef[1] * a - coef[2] * b) for a, b, w in mid)
        vol = m * hx * hy * hz
        print("%.5g,%d,%.5g,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,%.2f,%.2f,%.5f,%.5f,%.5f,%d,%d" % (
            t, m, vol, c[0], c[1], c[2], u[0], u[1], u[2], tilt, ang, bend, gcyl, gbase,
            gcyl < hx, gbase < hy))


def probes(outdir):
    """Every probe sample: underside and top (psi = 0 crossings) on the three vertical lines,
    and the velocity at the deepest point (largest psi) of the centre line."""
    cols = {}
    for name in ("left", "centre", "right"):
        rows = {}
        with open(os.path.join(outdir, "probe_%s.csv" % name)) as f:
            head = f.readline().strip().split(",")
            for line in f:
                r = dict(zip(head, (float(v) for v in line.split(","))))
                rows.setdefault(r["t"], []).append(r)
        cols[name] = rows
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
    cyl = (0.035, 0.0375, 0.01)
    if "--cylinder" in args:
        i = args.index("--cylinder")
        cyl = tuple(float(v) for v in args[i + 1:i + 4])
    if "--probes" in args:
        probes(args[0])
    else:
        analyse(args[0], cyl)
