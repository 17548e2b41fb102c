# Check: at constant density with walls, L = sum_d K (x) M (x) M with K = D^T D, M = A^T A,
# and K v = lambda E v gives V^T M V = I - Lambda/4, so L is diagonal in V (x) V (x) V.
import sys
from exact_mg import *
import scipy.linalg as sl
n=int(sys.argv[1]); L,G,B=build(n,1.0)
D=np.zeros((n-1,n)); A=np.zeros((n-1,n))
for i in range(n-1): D[i,i]=-1; D[i,i+1]=1; A[i,i]=A[i,i+1]=0.5
K=D.T@D; M=A.T@A; E=np.diag(np.r_[0.5,np.ones(n-2),0.5])
print("M == E - K/4:", np.abs(M-(E-K/4)).max())
lam,V=sl.eigh(K,E)
I=np.eye(n); kron=lambda a,b,c: np.kron(np.kron(a,b),c)
# cell index (i*n+j)*n+k -> x is the slowest
L27 = kron(K,M,M)+kron(M,K,M)+kron(M,M,K)
print("L == sum K(x)M(x)M (x/16 for h,1/4 scaling):", np.abs(L.toarray()-L27/4).max()/np.abs(L27).max())
mu=1-lam/4
Phi=kron(V,V,V); Dg=(np.add.outer(np.add.outer(np.kron(lam,1)*0,0),0))
d=(lam[:,None,None]*mu[None,:,None]*mu[None,None,:]+mu[:,None,None]*lam[None,:,None]*mu[None,None,:]+mu[:,None,None]*mu[None,:,None]*lam[None,None,:]).ravel()
print("Phi^T L27 Phi diagonal error:", np.abs(Phi.T@L27@Phi-np.diag(d)).max(), " zero eigenvalues:", (np.abs(d)<1e-10).sum(), "(n_x+n_y+n_z-1 =", 3*n-2, ")")
Ld=L.toarray(); print("ratio fit:", (Ld*L27).sum()/(L27*L27).sum(), "err after fit", np.abs(Ld-L27*(Ld*L27).sum()/(L27*L27).sum()).max())
