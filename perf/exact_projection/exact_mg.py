# Prototype: preconditioners for the exact semi-staggered operator L = G^T B G
# (cells n^3, no-slip walls: interior nodes only).
import numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spla, sys, time

def build(n, rho_ratio=1.0):
    N = n
    cid = lambda i,j,k: (i*N + j)*N + k
    rows=[]; cols=[]; vals=[]; r=0
    nodes = [(a,b,c) for a in range(1,N) for b in range(1,N) for c in range(1,N)]
    # node (a,b,c) sits between cells a-1,a ; b-1,b ; c-1,c
    binv = []
    for (a,b,c) in nodes:
        x=(a)/N; y=b/N; z=c/N
        rho = rho_ratio if (x<0.5 and z<0.5) else 1.0
        for d in range(3):
            for s in (0,1):
                for t in (0,1):
                    for hi in (0,1):
                        idx=[0,0,0]
                        o=[e for e in range(3) if e!=d]
                        idx[d]=(a,b,c)[d]-1+hi
                        idx[o[0]]=(a,b,c)[o[0]]-1+s
                        idx[o[1]]=(a,b,c)[o[1]]-1+t
                        rows.append(r); cols.append(cid(*idx)); vals.append((1 if hi else -1)*0.25)
            binv.append(1.0/rho); r+=1
    G = sp.csr_matrix((vals,(rows,cols)),shape=(r,N**3))
    B = sp.diags(binv)
    L = (G.T@B@G).tocsr()
    return L, G, B

def coords(n):
    i,j,k = np.meshgrid(np.arange(n),np.arange(n),np.arange(n),indexing='ij')
    return np.stack([i.ravel(),j.ravel(),k.ravel()],1).astype(float)

def aggregates(X, block):
    # X: point coords (ints on level grid), block: size per axis (1 = no coarsening)
    key = np.floor(X/np.array(block)).astype(int)
    _, agg = np.unique(key, axis=0, return_inverse=True)
    Xc = np.array([X[agg==a].mean(0) for a in range(agg.max()+1)])
    return agg.ravel(), np.floor(Xc/np.array(block)+1e-9)  # coarse coords on coarse grid

def tentative(agg, Bv):
    nagg = agg.max()+1; m = Bv.shape[1]
    rows=[];cols=[];vals=[]; Bc = np.zeros((nagg*m, m))
    for a in range(nagg):
        ids = np.where(agg==a)[0]
        Q,R = np.linalg.qr(Bv[ids])
        k = min(m, len(ids))
        for c in range(k):
            rows+=list(ids); cols+=[a*m+c]*len(ids); vals+=list(Q[:,c])
        Bc[a*m:a*m+k] = R[:k]
    P = sp.csr_matrix((vals,(rows,cols)),shape=(len(agg),nagg*m))
    return P, Bc

class MG:
    def __init__(self, A, X, block, Bv, filt=None, smooth=True, minsize=64):
        self.levels=[]; scale=abs(A).max()
        while A.shape[0] > minsize:
            agg, Xc = aggregates(X, block)
            if agg.max()+1 >= A.shape[0]: break
            Pt, Bc = tentative(agg, Bv)
            if smooth:
                Af = A if filt is None else filt(A, X)
                Dinv = sp.diags(1.0/Af.diagonal())
                Ds=sp.diags(1/np.sqrt(Af.diagonal())); lam = spla.eigsh(Ds@Af@Ds, k=1, which='LM', return_eigenvectors=False, tol=1e-3)[0] if Af.shape[0]>50 else 2.0
                P = (Pt - (4/3/lam)*(Dinv@(Af@Pt))).tocsr()
            else: P = Pt
            self.levels.append((A, P))
            A = (P.T@A@P).tocsr(); X = np.repeat(Xc, Bv.shape[1], axis=0); Bv = Bc
            if filt is not None and Bv.shape[1] > 1: pass
        self.Ac = A.toarray(); w_,V_=np.linalg.eigh(self.Ac); keep=w_>1e-9*scale; self.Acp=(V_[:,keep]/w_[keep])@V_[:,keep].T
    def gs(self, A, x, b, fwd=True):
        d = getattr(A,'_l1',None)
        if d is None:
            d = np.asarray(abs(A).sum(1)).ravel(); A._l1 = d
        for _ in range(2): x = x + (b - A@x)/d
        return x
    def vcycle(self, b, l=0):
        if l == len(self.levels): return self.Acp@b
        A,P = self.levels[l]
        x = self.gs(A, np.zeros_like(b), b, True)
        x = x + P@self.vcycle(P.T@(b - A@x), l+1)
        return self.gs(A, x, b, False)

def cg(A, b, M, tol=1e-8, maxit=1000):
    x=np.zeros_like(b); r=b.copy(); z=M(r); p=z.copy(); rz=r@z; nb=np.linalg.norm(b)
    for it in range(1,maxit+1):
        Ap=A@p; al=rz/(p@Ap); x+=al*p; r-=al*Ap
        if np.linalg.norm(r)<tol*nb: return x,it
        z=M(r); rzn=r@z; p=z+(rzn/rz)*p; rz=rzn
    print('  capped, rel res', np.linalg.norm(r)/nb)
    return x,maxit
