# CG on the exact operator at a density jump, preconditioned by the exact constant-density
# operator's tensor-product (generalised-eigenvector) solve.
import sys
from exact_mg import *
import scipy.linalg as sl
def build2(n, ratio, shape):
    L,G,B = build(n,1.0)
    # node coordinates in build order: a,b,c in 1..n-1, 3 rows per node
    a,b,c = np.meshgrid(np.arange(1,n),np.arange(1,n),np.arange(1,n),indexing='ij')
    x,y,z = a.ravel()/n, b.ravel()/n, c.ravel()/n
    if shape=='block': heavy = (abs(x-0.5)<0.15)&(abs(y-0.5)<0.15)&(abs(z-0.5)<0.06)
    elif shape=='dam': heavy = (x<0.25)&(z<0.5)
    elif shape=='big': heavy = (x<0.6)&(z<0.8)
    elif shape=='balls': heavy = ((((x*4)%1-0.5)**2+((y*4)%1-0.5)**2+((z*4)%1-0.5)**2)<0.16)
    else: heavy = np.zeros_like(x,bool)
    if shape=='damsmooth':
        # signed distance to the box x<0.25, z<0.5 (inside positive), Heaviside over +-1.5 h
        dx=0.25-x; dz=0.5-z; phi=np.minimum(dx,dz); hh=1.0/n; eps=1.5*hh
        H=np.clip(0.5*(1+phi/eps+np.sin(np.pi*phi/eps)/np.pi),0,1); H[phi>eps]=1; H[phi<-eps]=0
        rho=1+(ratio-1)*H; binv=np.repeat(1.0/rho,3)
    else: binv = np.repeat(np.where(heavy,1.0/ratio,1.0),3)
    B=sp.diags(binv); return (G.T@B@G).tocsr(), G, B
n=int(sys.argv[1]); ratio=float(sys.argv[2]); shape=sys.argv[3]
L,G,B=build2(n,ratio,shape)
D=np.zeros((n-1,n)); A=np.zeros((n-1,n))
for i in range(n-1): D[i,i]=-1; D[i,i+1]=1; A[i,i]=A[i,i+1]=0.5
K=D.T@D; E=np.diag(np.r_[0.5,np.ones(n-2),0.5]); lam,V=sl.eigh(K,E); mu=1-lam/4
d=(lam[:,None,None]*mu[None,:,None]*mu[None,None,:]+mu[:,None,None]*lam[None,:,None]*mu[None,None,:]+mu[:,None,None]*mu[None,:,None]*lam[None,None,:])
dinv=np.where(d>1e-10*d.max(),1.0/np.where(d>1e-10*d.max(),d,1),0.0)
def T(x,W):  # apply W^T along each axis
    X=x.reshape(n,n,n)
    X=np.einsum('ia,ijk->ajk',W,X); X=np.einsum('jb,ajk->abk',W,X); X=np.einsum('kc,abk->abc',W,X); return X
def Tinv(X,W):
    X=np.einsum('ia,abc->ibc',W,X); X=np.einsum('jb,ibc->ijc',W,X); X=np.einsum('kc,ijc->ijk',W,X); return X.ravel()
Mpc0=lambda r: Tinv(dinv*T(r,V),V)
if len(sys.argv)>4:
    # cell coefficient: mean of 1/rho over the cell's corner nodes (from G^T B G's diagonal / const diagonal)
    L0=(G.T@G).tocsr(); sc=L.diagonal()/L0.diagonal(); sc=np.where(np.isfinite(sc),sc,1)
    if sys.argv[4]=='harm': pass
    q=1/np.sqrt(sc); Mpc=lambda r: q*Mpc0(q*r)
else: Mpc=Mpc0
rng=np.random.default_rng(1); u=rng.standard_normal(G.shape[0]); b=G.T@(B@u)
x,it=cg(L,b,Mpc); print(f"n={n} ratio={ratio} {shape}: tensor-preconditioned CG {it} its, rel res {np.linalg.norm(b-L@x)/np.linalg.norm(b):.1e}")
