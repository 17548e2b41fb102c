# Multiplicative symbol correction (issue 19, 2026-12-05): at one density A0 = C^T L0 C with
# C = sqrt(A0 / L0) (the ratio of the two operators' symbols in the generalised eigenbasis), so try
#   P = C^-1 L7(B)^-1 C^-T  (L7: the variable 7-point operator, solved exactly by splu).
#   mult_pc.py N RATIO SHAPE
# Exact at one density (1 iteration); a jump breaks it (C and L7(B) do not commute).
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
sys.argv = sys.argv[:4] + ['l7']
src = open(os.path.join(here, 'split_pc.py')).read().split("if mode=='fd'")[0]
exec(src.replace("__file__", repr(os.path.join(here, 'split_pc.py'))))
e1 = np.r_[0.5, np.ones(n-2), 0.5]
Ediag = (e1[:, None, None]*e1[None, :, None]*e1[None, None, :]).ravel()
ok = (dA > cut) & (dL > cut)
rinv = np.where(ok, np.sqrt(np.where(ok, dL, 1)/np.where(ok, dA, 1)), 0.0)
Cinv = lambda x: Ti(rinv*T(Ediag*x, V), V)          # V r^-1/2 V^T E x
CinvT = lambda x: Ediag*Ti(rinv*T(x, V), V)         # E V r^-1/2 V^T x
M = lambda r: Cinv(L7inv(CinvT(r)))
rng = np.random.default_rng(1); u = rng.standard_normal(G.shape[0]); b = G.T @ (B @ u)
x, it = cg(L, b, M); x0, it0 = cg(L, b, FDA)
print(f"n={n} ratio={ratio} {shape} C^-1 L7^-1 C^-T: {it} its (rel res {np.linalg.norm(b-L@x)/np.linalg.norm(b):.1e}); FD alone {it0}")
