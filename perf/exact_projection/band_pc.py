# Fast diagonalization as the global part, a local solve as the other (issue 19, 2026-12-04):
#   x = S r; x += A0^+ (r - A x); x += S^T (r - A x)
#   band_pc.py N RATIO SHAPE sgs-all|sgs-band|exact-band [WIDEN]
# sgs-*: one symmetric Gauss-Seidel sweep on all rows or on the band's (cells of intermediate
# 1/rho); exact-band: a direct solve on the band widened by WIDEN cells.
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
sys.argv = sys.argv[:4] + ['l7'] + sys.argv[4:]
src = open(os.path.join(here, 'split_pc.py')).read().split("if mode=='fd'")[0]
exec(src.replace("__file__", repr(os.path.join(here, 'split_pc.py'))))
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve_triangular
kind = sys.argv[5]; widen = int(sys.argv[6]) if len(sys.argv) > 6 else 0
Lc = L.tocsr()
band = ((sc > sc.min() * 1.0001) & (sc < sc.max() * 0.9999)).reshape(n, n, n)
for _ in range(widen):
    b2 = band.copy()
    for ax in range(3): b2 |= np.roll(band, 1, ax) | np.roll(band, -1, ax)
    band = b2
idx = np.arange(n**3) if kind == 'sgs-all' else np.where(band.ravel())[0]
Ab = Lc[idx][:, idx].tocsr()
if kind == 'exact-band':
    lub = spla.splu(Ab.tocsc())
    def S(r, x):
        x = x.copy(); x[idx] += lub.solve((r - Lc @ x)[idx]); return x
    ST = S
else:
    Lo, Up = sp.tril(Ab, format='csr'), sp.triu(Ab, format='csr')
    def S(r, x):
        x = x.copy(); x[idx] += spsolve_triangular(Lo, (r - Lc @ x)[idx], lower=True); return x
    def ST(r, x):
        x = x.copy(); x[idx] += spsolve_triangular(Up, (r - Lc @ x)[idx], lower=False); return x
def M(r):
    x = S(r, np.zeros_like(r)); x = x + FDA(r - Lc @ x); return ST(r, x)
rng = np.random.default_rng(1); u = rng.standard_normal(G.shape[0]); b = G.T @ (B @ u)
x, it = cg(L, b, M); x0, it0 = cg(L, b, FDA)
print(f"n={n} ratio={ratio} {shape} {kind} widen {widen} ({len(idx)} rows): {it} its; fast diagonalization alone {it0}")
