import sys
from exact_mg import *
n = int(sys.argv[1]); ratio = float(sys.argv[2]) if len(sys.argv)>2 else 1.0
mode = sys.argv[3] if len(sys.argv)>3 else 'all'
L,G,B = build(n, ratio)
rng=np.random.default_rng(1); u=rng.standard_normal(G.shape[0]); b = G.T@(B@u)
X = coords(n)
def filt_axis(c):
    def f(A, X):
        A = A.tocoo(); keep = X[A.row,c]==X[A.col,c]
        Ak = sp.csr_matrix((A.data[keep],(A.row[keep],A.col[keep])),shape=A.shape)
        drop = np.asarray(sp.csr_matrix((A.data[~keep],(A.row[~keep],A.col[~keep])),shape=A.shape).sum(1)).ravel()
        return (Ak + sp.diags(drop)).tocsr()
    return f
t=time.time()
if mode in ('all','base'):
    M0 = MG(L, X, (2,2,2), np.column_stack([np.ones(n**3), (-1.0)**X.sum(1)]))
    x,it = cg(L,b,M0.vcycle); print(f"n={n} ratio={ratio} SA [1, checkerboard] 2x2x2 (now): {it} its", flush=True)
if mode in ('all','add'):
    M0 = MG(L, X, (2,2,2), np.ones((n**3,1)))
    comps=[(None,M0)]
    for c in range(3):
        a,bb=[e for e in range(3) if e!=c]
        T = (-1.0)**(X[:,a]+X[:,bb])
        Af = (sp.diags(T)@L@sp.diags(T)).tocsr()
        blk=[2,2,2]; blk[c]=1
        comps.append((T, MG(Af, X, tuple(blk), np.ones((n**3,1)), filt=filt_axis(c))))
    T=(-1.0)**(X.sum(1)); Af=(sp.diags(T)@L@sp.diags(T)).tocsr()
    comps.append((T, MG(Af, X, (2,2,2), np.column_stack([np.ones(n**3), X-X.mean(0)]))))
    def Madd(r):
        z = np.zeros_like(r)
        for T,M in comps:
            z += M.vcycle(r) if T is None else T*M.vcycle(T*r)
        return z
    x,it = cg(L,b,Madd); print(f"n={n} ratio={ratio} additive 4 subspaces: {it} its", flush=True)
    # family only without the smooth part
print("time", time.time()-t)
