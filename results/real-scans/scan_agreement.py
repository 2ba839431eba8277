# How well the scans agree under a set of poses: for neighbours k frames apart (k = 1, 4, 8), the
# mean over pairs of the median point-to-plane distance (8-neighbour planes, matches within 1 m)
# and the share of points matched. Under the reference poses and under each run's estimate.
# Usage: /usr/bin/python3 scan_agreement.py SCENE_DIR [RUN_DIR ...]   (numpy, scipy)
import numpy as np, glob, sys
from scipy.spatial import cKDTree
d=sys.argv[1]
files=sorted(glob.glob(d+'/samples/LIDAR_TOP/*.pcd.bin'))[:36]
def loadP(f):
    P=np.loadtxt(f).reshape(-1,3,4)[:36]; T=np.zeros((len(P),4,4)); T[:,:3,:]=P; T[:,3,3]=1; return T
def load(f):
    a=np.fromfile(f,dtype=np.float32).reshape(-1,5)[:,:3].astype(np.float64)
    r=np.linalg.norm(a,axis=1); return a[(r>1.8)&(r<80)]
S=[load(f) for f in files]
def agree(T,off):
    rng=np.random.default_rng(0); res=[]
    for i in range(36-off):
        A=S[i][rng.choice(len(S[i]),6000,replace=False)]; B=S[i+off]
        Aw=A@T[i][:3,:3].T+T[i][:3,3]; Bw=B@T[i+off][:3,:3].T+T[i+off][:3,3]
        dd,idx=cKDTree(Bw).query(Aw,k=8); nb=Bw[idx]; c=nb.mean(1); X=nb-c[:,None,:]
        w,v=np.linalg.eigh(np.einsum('nki,nkj->nij',X,X)); n=v[:,:,0]
        pl=np.abs(np.einsum('ni,ni->n',Aw-c,n)); ok=dd[:,0]<1.0
        res.append((np.median(pl[ok]), ok.mean()))
    r=np.array(res); return r[:,0].mean(), r[:,1].mean()
for name,f in [('reference',d+'/reference_poses_lidar_world.txt')]+[(a,a+'/trajectories/optimised.kitti.txt') for a in sys.argv[2:]]:
    T=loadP(f)
    print(name, ' '.join('off%d: %.4f m (inl %.3f)'%((o,)+agree(T,o)) for o in (1,4,8)), flush=True)
