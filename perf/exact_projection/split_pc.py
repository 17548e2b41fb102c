# Split preconditioner (issue 19, 2026-12-04): P = L7^-1 + S (A0^+ - L0^+) S with L7 the variable
# 7-point operator (face coefficient: mean node 1/rho at its corners), L0 its one-density form (the same
# eigenvectors as A0, so P is exact at one density) and S = cell 1/sqrt(1/rho).
#   split_pc.py N RATIO SHAPE [fd|l7|split|noscale|mg]   (L7 solved exactly by splu, or by a V-cycle: mg)
import sys
from exact_mg import *
import scipy.linalg as sl, scipy.sparse.linalg as spla
exec(open(__import__('os').path.join(__import__('os').path.dirname(__file__),'tensor_pc.py')).read().split("n=int(sys.argv[1])")[0].split("from exact_mg import *")[1])
n=int(sys.argv[1]); ratio=float(sys.argv[2]); shape=sys.argv[3]; mode=sys.argv[4] if len(sys.argv)>4 else 'split'
L,G,B=build2(n,ratio,shape)
bn=B.diagonal()[::3]  # node 1/rho, nodes (a,b,c) a,b,c in 1..n-1, c fastest
bnode=np.zeros((n+1,n+1,n+1)); bnode[1:n,1:n,1:n]=bn.reshape(n-1,n-1,n-1)
cid=lambda i,j,k:(i*n+j)*n+k
rows=[];cols=[];vals=[]
for d in range(3):
    for i in range(n-1):
        for j in range(n):
            for k in range(n):
                idx=[0,0,0]; o=[e for e in range(3) if e!=d]
                # face between cells c0 and c1 along d
                c0=[0,0,0]; c0[d]=i; c0[o[0]]=j; c0[o[1]]=k
                c1=list(c0); c1[d]=i+1
                s=0.0
                for p in (0,1):
                    for q in (0,1):
                        nd=[0,0,0]; nd[d]=i+1; nd[o[0]]=j+p; nd[o[1]]=k+q
                        s+=0.25*bnode[tuple(nd)]
                a0=cid(*c0); a1=cid(*c1)
                rows+=[a0,a0,a1,a1]; cols+=[a0,a1,a0,a1]; vals+=[s,-s,-s,s]
L7=sp.csr_matrix((vals,(rows,cols)),shape=(n**3,n**3))
D=np.zeros((n-1,n)); 
for i in range(n-1): D[i,i]=-1; D[i,i+1]=1
K=D.T@D; E=np.diag(np.r_[0.5,np.ones(n-2),0.5]); lam,V=sl.eigh(K,E); mu=1-lam/4
l3=lambda f: f(0)+f(1)+f(2)
dA=(lam[:,None,None]*mu[None,:,None]*mu[None,None,:]+mu[:,None,None]*lam[None,:,None]*mu[None,None,:]+mu[:,None,None]*mu[None,:,None]*lam[None,None,:])
dL=lam[:,None,None]+lam[None,:,None]+lam[None,None,:]
cut=1e-10*dA.max()
invA=np.where(dA>cut,1/np.where(dA>cut,dA,1),0); invL=np.where(dL>cut,1/np.where(dL>cut,dL,1),0)
def T(x,W):
    X=x.reshape(n,n,n); X=np.einsum('ia,ijk->ajk',W,X); X=np.einsum('jb,ajk->abk',W,X); return np.einsum('kc,abk->abc',W,X)
def Ti(X,W):
    X=np.einsum('ia,abc->ibc',W,X); X=np.einsum('jb,ibc->ijc',W,X); return np.einsum('kc,ijc->ijk',W,X).ravel()
FDA=lambda r: Ti(invA*T(r,V),V); FDdiff=lambda r: Ti((invA-invL)*T(r,V),V)
L0=(G.T@G).tocsr(); sc=L.diagonal()/L0.diagonal(); sc=np.where(np.isfinite(sc),sc,1); s=1/np.sqrt(sc)
# L7 singular (Neumann): pin by adding a tiny multiple of the constant projector via lu on L7+eps
one=np.ones(n**3)/np.sqrt(n**3)
lu=spla.splu((L7+sp.csr_matrix(np.outer(one,one)*0) + 1e-12*sp.eye(n**3)).tocsc()) if mode!='mg' else None
def L7inv(r):
    r=r-one*(one@r); x=lu.solve(r); return x-one*(one@x)
if mode=='mg':
    X=coords(n); mg=MG(L7.tocsr(),X,(2,2,2),np.ones((n**3,1)))
    L7inv=lambda r: mg.vcycle(r-one*(one@r))
if mode=='fd': M=FDA
elif mode=='l7': M=L7inv
elif mode=='noscale': M=lambda r: L7inv(r)+FDdiff(r)
else: M=lambda r: L7inv(r)+s*FDdiff(s*r)
rng=np.random.default_rng(1); u=rng.standard_normal(G.shape[0]); b=G.T@(B@u)
x,it=cg(L,b,M); print(f"n={n} ratio={ratio} {shape} {mode}: {it} its, rel res {np.linalg.norm(b-L@x)/np.linalg.norm(b):.1e}")
