# Approximate projections at a smoothed ratio-1000 jump: the divergence D u left after
# u = u* - B G phi, with phi from the 7-point operator or from the dual-cell trilinear FE stiffness
# (AMReX's nodal operator in Voigt's arrangement: D B G plus hourglass terms), both solved exactly.
#   fe_div.py N RATIO SHAPE   (issue 19, 2026-12-05; perf/README.md "What AMReX's nodal projection solves")
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
sys.argv = sys.argv[:4] + ['l7']
src = open(os.path.join(here, 'split_pc.py')).read().split("if mode=='fd'")[0]
exec(src.replace("__file__", repr(os.path.join(here, 'split_pc.py'))))
import itertools
# Q1 stiffness of a unit cube, 2x2x2 Gauss: corners c in {0,1}^3 in the order of G's columns per node
q = [0.5 - 0.5/np.sqrt(3), 0.5 + 0.5/np.sqrt(3)]
corners = list(itertools.product((0, 1), repeat=3))
Ke = np.zeros((8, 8))
for x, y, z in itertools.product(q, q, q):
    gr = []
    for (a, b, c) in corners:
        fx = (x if a else 1 - x); fy = (y if b else 1 - y); fz = (z if c else 1 - z)
        gr.append([(1 if a else -1) * fy * fz, (1 if b else -1) * fx * fz, (1 if c else -1) * fx * fy])
    gr = np.array(gr); Ke += gr @ gr.T / 8
cid = lambda i, j, k: (i * n + j) * n + k
rows = []; cols = []; vals = []
bn = B.diagonal()[::3]
nodes = [(a, b, c) for a in range(1, n) for b in range(1, n) for c in range(1, n)]
for s_, (a, b, c) in zip(bn, nodes):
    ids = [cid(a - 1 + p, b - 1 + r, c - 1 + t) for (p, r, t) in corners]
    for u_ in range(8):
        for v_ in range(8):
            rows.append(ids[u_]); cols.append(ids[v_]); vals.append(s_ * Ke[u_, v_])
LFE = sp.csr_matrix((vals, (rows, cols)), shape=(n**3, n**3))
one = np.ones(n**3) / np.sqrt(n**3)
def solve(A, r):
    lu = spla.splu((A + 1e-12 * sp.eye(n**3)).tocsc()); r = r - one * (one @ r); x = lu.solve(r); return x - one * (one @ x)
rng = np.random.default_rng(1)
us = rng.standard_normal(G.shape[0])
for name, u0 in (('random u*', us),):
    d = G.T @ u0                     # -D u* (sign as in the prototype: L = G^T B G)
    print(f"n={n} ratio={ratio} {shape} {name}: |D u*| = {np.linalg.norm(d):.3e}")
    for nm, A in (('exact', L), ('7-point', L7), ('FE (AMReX-like)', LFE)):
        phi = solve(A, G.T @ (B @ u0))
        un = u0 - G @ phi                 # phi solves A phi = G^T B u*; the exact A = G^T B G leaves 0
        r = G.T @ (B @ un)
        print(f"  {nm:16s}: max |D B u| after / before = {abs(r).max()/abs(G.T@(B@u0)).max():.3e}, L2 {np.linalg.norm(r)/np.linalg.norm(G.T@(B@u0)):.3e}")
a_, b_, c_ = np.meshgrid(np.arange(1, n), np.arange(1, n), np.arange(1, n), indexing='ij')
x_, y_, z_ = a_.ravel() / n, b_.ravel() / n, c_.ravel() / n
for name, comp in (('smooth u* (one mode)', lambda: np.stack([np.sin(np.pi*x_)*np.cos(2*np.pi*y_), np.cos(np.pi*z_)*np.sin(np.pi*y_), np.sin(2*np.pi*x_)*np.sin(np.pi*z_)], 1).ravel()),):
    u0 = comp()
    print(f"{name}:")
    for nm, A in (('7-point', L7), ('FE (AMReX-like)', LFE)):
        phi = solve(A, G.T @ (B @ u0)); un = u0 - G @ phi; r = G.T @ (B @ un)
        print(f"  {nm:16s}: max |D B u| after / before = {abs(r).max()/abs(G.T@(B@u0)).max():.3e}, L2 {np.linalg.norm(r)/np.linalg.norm(G.T@(B@u0)):.3e}")
