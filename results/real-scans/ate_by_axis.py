# ATE (SE(3) Umeyama alignment of positions, as protocol §4) split by axis, and the ATE of the
# horizontal components alone; the vertical extent of both trajectories.
# Usage: /usr/bin/python3 ate_by_axis.py GT.kitti.txt EST.kitti.txt [EST2 ...]
import numpy as np, sys
def loadP(f):
    P=np.loadtxt(f).reshape(-1,3,4); return P[:,:,3], P[:,:,:3]
g,_=loadP(sys.argv[1]); 
for f in sys.argv[2:]:
    e,_=loadP(f); n=min(len(g),len(e)); g2=g[:n]; e2=e[:n]
    mg,me=g2.mean(0),e2.mean(0); H=(e2-me).T@(g2-mg); U,S,Vt=np.linalg.svd(H); D=np.eye(3); D[2,2]=np.sign(np.linalg.det(Vt.T@U.T)); R=Vt.T@D@U.T
    a=(e2-me)@R.T+mg; r=a-g2
    print(f, 'ATE %.3f  rms x %.3f y %.3f z %.3f | xy-only ATE %.3f'%(np.sqrt((r**2).sum(1).mean()), *np.sqrt((r**2).mean(0)), np.sqrt((r[:,:2]**2).sum(1).mean())))
    print('  gt z range %.3f m, est z range (aligned) %.3f m'%(np.ptp(g2[:,2]), np.ptp(a[:,2])))
