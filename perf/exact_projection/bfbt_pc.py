# BFBt / least-squares commutator (issue 19, 2026-12-05): A = G^T B G with B = diag(1/rho) is a Schur
# complement with a diagonal "F^-1" = B, so Elman's BFBt approximation applies with fast
# diagonalization for the inner solves:  P = A0^+ (G^T W G) A0^+,  W = diag(rho) (exact at one density).
#   bfbt_pc.py N RATIO SHAPE [rho|sqrt]   (sqrt: the weighted form W = I, scaled by sqrt(rho) cellwise)
import os, sys
here = os.path.dirname(os.path.abspath(__file__))
kind = sys.argv[4] if len(sys.argv) > 4 else 'rho'
sys.argv = sys.argv[:4] + ['l7']
src = open(os.path.join(here, 'split_pc.py')).read().split("if mode=='fd'")[0]
exec(src.replace("__file__", repr(os.path.join(here, 'split_pc.py'))).replace("lu=spla.splu", "lu=None and spla.splu"))
rho = 1.0 / B.diagonal()
W = sp.diags(rho); GWG = (G.T @ W @ G).tocsr()
if kind == 'rho':
    M = lambda r: FDA(GWG @ FDA(r))
rng = np.random.default_rng(1); u = rng.standard_normal(G.shape[0]); b = G.T @ (B @ u)
x, it = cg(L, b, M); x0, it0 = cg(L, b, FDA)
print(f"n={n} ratio={ratio} {shape} BFBt({kind}): {it} its (rel res {np.linalg.norm(b-L@x)/np.linalg.norm(b):.1e}); FD alone {it0}")
if len(sys.argv) > 5 or kind == 'rho':
    lu7 = spla.splu((L7 + 1e-12*sp.eye(n**3)).tocsc())
    def L7e(r):
        r = r - one*(one@r); x = lu7.solve(r); return x - one*(one@x)
    def Msym(r):
        x = L7e(r); x = x + FDA(r - L @ x); return x + L7e(r - L @ x)
    x, it = cg(L, b, Msym)
    print(f"   L7^-1, FD, L7^-1 (multiplicative): {it} its")
    def Msym2(r):
        x = FDA(r); x = x + L7e(r - L @ x); return x + FDA(r - L @ x)
    x, it = cg(L, b, Msym2)
    print(f"   FD, L7^-1, FD (multiplicative): {it} its")
