# Does deskewing lower the scans' disagreement under the reference poses? For each timing
# hypothesis (spin direction, azimuth where the sweep starts, reference time within the 50 ms
# sweep) every scan is deskewed with the reference poses' own velocity, and the mean over
# neighbouring pairs of the median point-to-plane distance is printed ('none': as published).
# Usage: /usr/bin/python3 deskew_check.py [nuScenes scene folder]   (numpy, scipy)
import numpy as np, glob, sys
from scipy.spatial import cKDTree
d=sys.argv[1] if len(sys.argv)>1 else '../shared/data/real/nuscenes-mini-scene-0916'
files=sorted(glob.glob(d+'/samples/LIDAR_TOP/*.pcd.bin'))[:36]
P=np.loadtxt(d+'/reference_poses_lidar_world.txt').reshape(-1,3,4)[:36]
T=np.zeros((len(P),4,4)); T[:,:3,:]=P; T[:,3,3]=1
times=np.loadtxt(d+'/times.txt')[:36]
def load(f):
    a=np.fromfile(f,dtype=np.float32).reshape(-1,5)[:,:3].astype(np.float64)
    r=np.linalg.norm(a,axis=1); return a[(r>1.8)&(r<80)]
S=[load(f) for f in files]
def logR(R):
    c=np.clip((np.trace(R)-1)/2,-1,1); th=np.arccos(c)
    if th<1e-9: return np.zeros(3)
    w=np.array([R[2,1]-R[1,2],R[0,2]-R[2,0],R[1,0]-R[0,1]])/(2*np.sin(th)); return w*th
def expR(w):
    th=np.linalg.norm(w)
    if th<1e-12: return np.eye(3)
    k=w/th; K=np.array([[0,-k[2],k[1]],[k[2],0,-k[0]],[-k[1],k[0],0]])
    return np.eye(3)+np.sin(th)*K+(1-np.cos(th))*K@K
# per-frame twist in the lidar frame (velocity per second), from GT neighbours
tw=[]
for i in range(36):
    a,b=max(i-1,0),min(i+1,35)
    Trel=np.linalg.inv(T[i])@T[b] if b>i else np.eye(4)
    Trel0=np.linalg.inv(T[a])@T[i] if i>a else np.eye(4)
    # central estimate: average of the motion i->b and a->i
    dt=times[b]-times[a]
    M=np.linalg.inv(T[a])@T[b]
    # express in frame i approx: use log of M rotated into frame i
    Ri=np.linalg.inv(T[i])[:3,:3]@T[a][:3,:3]
    v=Ri@M[:3,3]/dt; w=Ri@logR(M[:3,:3])/dt
    tw.append((v,w))
def deskew(p,i,direction,start_deg,ref):
    az=np.degrees(np.arctan2(p[:,1],p[:,0]))
    frac=((direction*(az-start_deg))%360)/360.0  # 0 at sweep start
    dt=(frac-ref)*0.05
    v,w=tw[i]
    out=np.empty_like(p)
    # small-motion: p_ref = R(w dt) p + v dt
    for k0 in range(0,len(p),1):
        break
    wdt=np.outer(dt,w)  # approx rotation by first order
    out=p+np.cross(wdt,p)+np.outer(dt,v)
    return out
rng=np.random.default_rng(0)
def residual(clouds):
    res=[]
    for i in range(35):
        A=clouds[i]; B=clouds[i+1]
        A=A[rng.choice(len(A),8000,replace=False)]
        Aw=(T[i][:3,:3]@A.T).T+T[i][:3,3]
        Bw=(T[i+1][:3,:3]@B.T).T+T[i+1][:3,3]
        tree=cKDTree(Bw); dd,idx=tree.query(Aw,k=8)
        # point-to-plane from the 8 neighbours' plane
        nb=Bw[idx]; c=nb.mean(1); X=nb-c[:,None,:]
        C=np.einsum('nki,nkj->nij',X,X); wv,vv=np.linalg.eigh(C); n=vv[:,:,0]
        pl=np.abs(np.einsum('ni,ni->n',Aw-c,n))
        ok=dd[:,0]<1.0
        res.append(np.median(pl[ok]))
    return np.mean(res)
print('speed m/s', np.mean([np.linalg.norm(v) for v,w in tw]), 'yaw deg/s', np.degrees(np.mean([abs(w[2]) for v,w in tw])))
print('none', residual(S))
for direction in (-1,1):
    for start in (0,90,180,270):
        for ref in (0.0,0.5,1.0):
            C=[deskew(S[i],i,direction,start,ref) for i in range(36)]
            print(direction,start,ref, round(residual(C),5), flush=True)
