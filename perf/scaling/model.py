#!/usr/bin/python3
"""A scaling model built from counts (perf/scaling/traffic.py): per step and rank, compute from
the one-rank per-cell rates measured here, messages and bytes from laws checked against the
counts at 1-64 ranks, and a stated network; projected to 4,096 ranks, strong and weak, for
the fast diagonalization (the default) and multigrid on the same exact operator.

    perf/scaling/model.py [--in DIR] [--alpha 2e-6] [--beta 25e9]   # prints the tables (markdown)

Laws (each checked against the measured counts in the first table):
  halo (point to point) bytes: (b0 + b1 its) times the neighbours' faces with their ghosts,
      sum of (m_a + 5)(m_b + 5) over an interior rank's neighbours; messages: (k0 + k1 its)
      times the neighbours (2 per split axis); fit over the runs on 2-64 ranks (its: CG
      iterations a step; multigrid exchanges halos on every level of every V-cycle);
  transposes (all to all): per preconditioner application, the moves blocks -> x -> (c ->) s
      pencils and back, messages and bytes counted from the same boxes as the code builds
      (grid.cpp chooseDims, fast_diagonalization.cpp pencilGrid and split) times the
      applications a step (measured on 2 ranks, per CG iteration);
  reductions (collective): calls a step = c0 + c1 its (fit; c1 = 3 where its do not vary),
      each 2 ceil(log2 P) latencies (recursive doubling).
Time = compute + messages alpha + bytes / beta (no overlap: an upper bound); compute = cells a rank
x one-rank seconds per cell (the projection per cell and CG iteration fit as a + b n for the
fast diagonalization: its dense 1-D transforms are O(n) a cell).
"""
import argparse
import csv
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = ["properties", "advection", "momentum", "projection", "corrections", "diagnostics"]


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def choose_dims(size, cells):
    """src/core/grid.cpp chooseDims: the factorisation with the fewest halo faces, ties to x split least."""
    best, out = -1, None
    for a in range(1, size + 1):
        if size % a:
            continue
        for b in range(1, size // a + 1):
            if (size // a) % b:
                continue
            c = size // a // b
            p = (a, b, c)
            if any(cells[d] < p[d] for d in range(3)):
                continue
            nx, ny, nz = cells[0] / a, cells[1] / b, cells[2] / c
            faces = (ny * nz if a > 1 else 0) + (nx * nz if b > 1 else 0) + (nx * ny if c > 1 else 0)
            if best < 0 or faces < best - 1e-12:
                best, out = faces, p
    return out


def even(m, parts, p):  # fast_diagonalization.cpp split: [lo, lo + n)
    lo = m * p // parts
    return lo, m * (p + 1) // parts - lo


def block_box(cells, dims, rank):  # grid.cpp: MPI_Cart rank order (z fastest), remainder first
    crd = (rank // (dims[1] * dims[2]), (rank // dims[2]) % dims[1], rank % dims[2])
    lo, n = [], []
    for d in range(3):
        base, rem = cells[d] // dims[d], cells[d] % dims[d]
        lo.append(crd[d] * base + min(crd[d], rem))
        n.append(base + (1 if crd[d] < rem else 0))
    return lo, n


def pencil_grid(size, n, s, c, slab_ranks=8):  # fast_diagonalization.cpp pencilGrid
    cap2, cap1 = min(n[s], n[c]), min(n[0], n[c])
    if size <= min(cap2, slab_ranks):
        return 1, size
    best = 0
    p1 = 1
    while p1 <= cap1 and p1 * p1 <= size:
        if size % p1 == 0 and size // p1 <= cap2:
            best = p1
        p1 += 1
    if best:
        return best, size // best
    return max(1, min(cap1, size // cap2)), cap2


def layouts(cells, size, s=2, c=1):
    """Every rank's box in each layout: blocks, x pencils, (c pencils,) s pencils."""
    dims = choose_dims(size, cells)
    p1, p2 = pencil_grid(size, cells, s, c)

    def pencil(p, e1, e2):
        if p >= p1 * p2:
            return [0, 0, 0], [0, 0, 0]
        lo, n = [0, 0, 0], list(cells)
        lo[e1], n[e1] = even(cells[e1], p1, p % p1)
        lo[e2], n[e2] = even(cells[e2], p2, p // p1)
        return lo, n
    blocks = [block_box(cells, dims, p) for p in range(size)]
    xs = [pencil(p, c, s) for p in range(size)]
    mids = [pencil(p, 0, s) for p in range(size)] if p1 > 1 else None
    ss = [pencil(p, 0, c) for p in range(size)]
    seq = [blocks, xs] + ([mids] if mids else []) + [ss]
    return seq, dims, (p1, p2)


def overlap(a, b):
    v = 1
    for d in range(3):
        lo, hi = max(a[0][d], b[0][d]), min(a[0][d] + a[1][d], b[0][d] + b[1][d])
        if hi <= lo:
            return 0
        v *= hi - lo
    return v


def transpose_counts(cells, size, word=4, sample=48):
    """Per application, the most over (sampled) ranks: messages and bytes sent, both ways."""
    seq, dims, grid = layouts(cells, size)
    ranks = range(size) if size <= sample else sorted({int(i * (size - 1) / (sample - 1)) for i in range(sample)})
    most = (0, 0)
    for p in ranks:
        msgs = byts = 0
        for src, dst in zip(seq, seq[1:]):
            for q in range(size):
                if q == p:
                    continue
                f, b = overlap(src[p], dst[q]), overlap(dst[p], src[q])  # forward, backward
                msgs += (f > 0) + (b > 0)
                byts += (f + b) * word
        most = max(most, (msgs, byts))
    return most, dims, grid


def halo_faces(cells, size):
    """Neighbours and sum of the neighbours' faces with ghosts, for an interior rank."""
    dims = choose_dims(size, cells)
    m = [cells[d] / dims[d] for d in range(3)]
    nb, faces = 0, 0.0
    for d in range(3):
        k = min(2, dims[d] - 1)
        a, b = [e for e in range(3) if e != d]
        nb += k
        faces += k * (m[a] + 5) * (m[b] + 5)
    return nb, faces


def lin(xs, ys, slope=0.0):
    """Least-squares y = y0 + y1 x; where x does not vary, y1 = slope and y0 the mean rest."""
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx <= 1e-9 * max(1.0, mx * mx):
        return my - slope * mx, slope
    y1 = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return my - y1 * mx, y1


def num(r, k):
    v = r.get(k, "")
    return float(v) if v not in ("", None) else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--in", dest="inp", default=os.path.join(HERE, "results"))
    ap.add_argument("--alpha", type=float, default=2e-6, help="latency per message, s")
    ap.add_argument("--beta", type=float, default=25e9, help="bandwidth per rank, bytes/s")
    a = ap.parse_args()
    rows, rates = read(os.path.join(a.inp, "traffic.csv")), read(os.path.join(a.inp, "rates.csv"))
    out = []
    P = lambda *x: out.append(" ".join(str(v) for v in x))  # noqa: E731
    P("Network: latency %.1f us a message, %.0f GB/s a rank; compute: one-rank rates on this machine.\n"
      % (a.alpha * 1e6, a.beta / 1e9))
    model = {}
    for scene in ("falling_block", "dam_break"):
        for var in ("fd", "mg"):
            rs = sorted([r for r in rows if r["scene"] == scene and r["variant"] == var], key=lambda r: int(r["ranks"]))
            rt = sorted([r for r in rates if r["scene"] == scene and r["variant"] == var], key=lambda r: int(r["n"]))
            if not rs or not rt:
                continue
            n0 = int(rs[0]["n"])
            cells = (n0, n0, n0)
            multi = [r for r in rs if int(r["ranks"]) > 1]
            # halo law: per neighbour k0 + k1 its messages, per face cell b0 + b1 its bytes;
            # reductions c0 + c1 its calls (least squares over the runs on more than one rank;
            # where the iterations do not change with the ranks, k1 = b1 = 0 and c1 = 3, CG's
            # two dot products and a norm an iteration)
            its_ = [num(r, "its") for r in multi]
            nbs = [halo_faces(cells, int(r["ranks"])) for r in multi]
            k_m = lin([i for i in its_], [num(r, "total:point_to_point:messages_max") / max(nb, 1) for r, (nb, fb) in zip(multi, nbs)])
            k_h = lin(its_, [num(r, "total:point_to_point:bytes_max") / fb for r, (nb, fb) in zip(multi, nbs)])
            c = lin(its_, [num(r, "total:collective:messages_max") for r in multi], slope=3.0)
            # applications of the preconditioner a step (transposes): measured / per application
            apps = None
            P("### %s, %s: counts a step and rank (the most over the ranks), measured and by the laws\n" % (scene, var))
            P("| ranks | decomposition | FD rank grid | CG its | halo messages | law | halo MB | law | "
              "transposes messages | law | transposes MB | law | reductions | law |")
            P("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
            for r in rs:
                p = int(r["ranks"])
                nbp, fp = halo_faces(cells, p)
                its = num(r, "its")
                (tm, tb), dims, grid = transpose_counts(cells, p) if var == "fd" else ((0, 0), choose_dims(p, cells), (0, 0))
                if var == "fd" and p > 1 and tm > 0 and apps is None:
                    apps = num(r, "total:all_to_all:messages_max") / tm / its  # applications an iteration
                ap_ = apps * its if apps else 0
                P("| %d | %s | %s | %.1f | %.0f | %.0f | %.3f | %.3f | %.0f | %.0f | %.3f | %.3f | %.0f | %.0f |" % (
                    p, "x".join(map(str, dims)), "x".join(map(str, grid)) if var == "fd" else "-", its,
                    num(r, "total:point_to_point:messages_max"), (k_m[0] + k_m[1] * its) * nbp,
                    num(r, "total:point_to_point:bytes_max") / 1e6, (k_h[0] + k_h[1] * its) * fp / 1e6,
                    num(r, "total:all_to_all:messages_max"), ap_ * tm,
                    num(r, "total:all_to_all:bytes_max") / 1e6, ap_ * tb / 1e6,
                    num(r, "total:collective:messages_max"), (c[0] + c[1] * its) if p > 1 else 0))
            P("")
            # compute rates at one rank: per cell a step outside the projection; per cell and
            # iteration in it (a + b n for FD: least squares over the three n)
            ns = [int(r["n"]) for r in rt]
            # the solver's set-up (matrix refill, multigrid hierarchy: in the momentum stage, every
            # step the density changes) counts as the projection's, per cell and step
            setup = [num(r, "poisson_setup") / n ** 3 for r, n in zip(rt, ns)]
            other = [sum(num(r, "seconds:" + s) for s in TOP if s != "projection") / n ** 3 - su
                     for r, n, su in zip(rt, ns, setup)]
            proj = [num(r, "seconds:projection") / n ** 3 / max(num(r, "its"), 1) for r, n in zip(rt, ns)]
            its = [num(r, "its") for r in rt]
            if var == "fd":
                mx, my = sum(ns) / len(ns), sum(proj) / len(proj)
                b = sum((x - mx) * (y - my) for x, y in zip(ns, proj)) / sum((x - mx) ** 2 for x in ns)
                pa, pb_ = my - b * mx, b
            else:
                pa, pb_ = sum(proj) / len(proj), 0.0
            lx = [math.log(x) for x in ns]
            ly = [math.log(max(y, 1)) for y in its]
            mlx, mly = sum(lx) / len(lx), sum(ly) / len(ly)
            alpha_its = sum((x - mlx) * (y - mly) for x, y in zip(lx, ly)) / sum((x - mlx) ** 2 for x in lx)
            model[(scene, var)] = dict(other=sum(other) / len(other), setup=sum(setup) / len(setup), pa=pa, pb=pb_, its0=math.exp(mly - alpha_its * mlx),
                                       alpha_its=alpha_its, k_h=k_h, k_m=k_m, c=c, apps=apps or 0,
                                       rates=list(zip(ns, its, other, proj)))
    for (scene, var), m in model.items():
        P("One-rank rates, %s %s (n: CG its a step, s a cell-step outside the projection, s a cell and iteration"
          " in it): %s; its ~ %.1f n^%.2f; projection %.3g + %.3g n s a cell and iteration, set-up %.3g s a cell-step" % (
              scene, var, "; ".join("%d: %.1f, %.3g, %.3g" % t for t in m["rates"]), m["its0"], m["alpha_its"], m["pa"],
              m["pb"], m["setup"]))
    P("")

    def step_time(scene, var, n, p):
        m = model[(scene, var)]
        cells = n ** 3 / p
        its = m["its0"] * n ** m["alpha_its"]
        comp_proj = cells * (its * (m["pa"] + m["pb"] * n) + m["setup"])
        comp_other = cells * m["other"] + comp_proj
        nb, fb = halo_faces((n, n, n), p) if p > 1 else (0, 0)
        halo = (m["k_m"][0] + m["k_m"][1] * its) * nb * a.alpha + (m["k_h"][0] + m["k_h"][1] * its) * fb / a.beta
        tr = 0.0
        if var == "fd" and p > 1:
            (tm, tb), _, _ = transpose_counts((n, n, n), p)
            apps = m["apps"] * its
            tr = apps * (tm * a.alpha + tb / a.beta)
        red = (m["c"][0] + m["c"][1] * its) * 2 * math.ceil(math.log2(p)) * a.alpha if p > 1 else 0.0
        return comp_other, comp_proj, halo, tr, red, its
    for kind, cases in (("Strong scaling", [("falling_block", 75), ("dam_break", 64), ("falling_block", 256)]),):
        P("### %s: seconds a step, the projection's share (compute + communication)\n" % kind)
        P("| scene | n^3 | preconditioner | ranks | CG its | compute | halo | transposes | reductions | total | "
          "projection share | speed-up |")
        P("|---|---|---|---|---|---|---|---|---|---|---|---|")
        for scene, n in cases:
            for var in ("fd", "mg"):
                if (scene, var) not in model:
                    continue
                t1 = None
                for p in (1, 8, 64, 512, 4096):
                    if n ** 3 / p < 8 ** 3:
                        continue
                    c, cp, h, tr, r, its = step_time(scene, var, n, p)
                    tot = c + h + tr + r
                    t1 = t1 or tot
                    P("| %s | %d | %s | %d | %.0f | %.3g | %.2g | %.2g | %.2g | %.3g | %.0f %% | %.0f |" % (
                        scene, n, var, p, its, c, h, tr, r, tot, 100 * (cp + tr + r) / tot, t1 / tot))
        P("")
    P("### Weak scaling: 64^3 cells a rank (n = 64 P^(1/3)), seconds a step\n")
    P("| scene | ranks | n | FD its | FD s/step | FD projection share | MG its | MG s/step | MG projection share | cheaper |")
    P("|---|---|---|---|---|---|---|---|---|---|")
    for scene in ("falling_block", "dam_break"):
        if (scene, "fd") not in model or (scene, "mg") not in model:
            continue
        for p in (1, 8, 64, 512, 4096):
            n = round(64 * p ** (1 / 3))
            res = {}
            for var in ("fd", "mg"):
                c, cp, h, tr, r, its = step_time(scene, var, n, p)
                res[var] = (its, c + h + tr + r, (cp + tr + r) / (c + h + tr + r))
            P("| %s | %d | %d | %.0f | %.3g | %.0f %% | %.0f | %.3g | %.0f %% | %s |" % (
                scene, p, n, res["fd"][0], res["fd"][1], 100 * res["fd"][2], res["mg"][0], res["mg"][1],
                100 * res["mg"][2], "multigrid" if res["mg"][1] < res["fd"][1] else "fast diagonalization"))
    P("")
    # Where multigrid becomes the cheaper projection, per scene (one rank's compute: the
    # switch does not depend on the ranks while compute dominates).
    for scene in ("falling_block", "dam_break"):
        if (scene, "fd") not in model or (scene, "mg") not in model:
            continue
        sw = None
        for n in range(32, 4097, 8):
            if step_time(scene, "mg", n, 1)[1] < step_time(scene, "fd", n, 1)[1]:
                sw = n
                break
        P("Switch (%s): multigrid's projection is the cheaper from n = %s on (one rank's compute)." % (
            scene, sw if sw else "never up to 4096"))
    print("\n".join(out))


if __name__ == "__main__":
    sys.exit(main())
