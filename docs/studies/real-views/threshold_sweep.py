# Decision-threshold sweep on rendered test views: CD (both directions), F-score, as sgnlf eval computes them.
import struct, array, math, sys
def load(p):
    d=open(p,'rb').read(); hl=struct.unpack('<H',d[8:10])[0]
    a=array.array('f'); a.frombytes(d[10+hl:]); return a
H,W,FU,FOV=int(sys.argv[2]),int(sys.argv[3]),float(sys.argv[4]),float(sys.argv[5])
dirs=[]
for r in range(H):
    al=(FU-r*FOV/H)*math.pi/180
    for c in range(W):
        b=-(c-W/2)/W*2*math.pi
        dirs.append((math.cos(al)*math.cos(b),math.cos(al)*math.sin(b),math.sin(al)))
def pts(rng,mask):
    return [(rng[p]*dirs[p][0],rng[p]*dirs[p][1],rng[p]*dirs[p][2]) for p in range(H*W) if mask[p] and rng[p]>0]
def grid(P,s):
    g={}
    for q in P: g.setdefault((int(math.floor(q[0]/s)),int(math.floor(q[1]/s)),int(math.floor(q[2]/s))),[]).append(q)
    return g
def nn2(P,Q,s=1.0):
    g=grid(Q,s); out=[]
    for q in P:
        k=(int(math.floor(q[0]/s)),int(math.floor(q[1]/s)),int(math.floor(q[2]/s)))
        best=None; rad=1
        while rad<=6:
            for i in range(k[0]-rad,k[0]+rad+1):
                for j in range(k[1]-rad,k[1]+rad+1):
                    for l in range(k[2]-rad,k[2]+rad+1):
                        if max(abs(i-k[0]),abs(j-k[1]),abs(l-k[2]))!=rad and rad>1: continue
                        for p in g.get((i,j,l),()):
                            d=(p[0]-q[0])**2+(p[1]-q[1])**2+(p[2]-q[2])**2
                            if best is None or d<best: best=d
            if best is not None and best<=(rad*s)**2: break
            rad+=1
        if best is None or best>(6*s)**2:
            best=min((p[0]-q[0])**2+(p[1]-q[1])**2+(p[2]-q[2])**2 for p in Q)
        out.append(best)
    return out
run=sys.argv[1]; frames=sys.argv[6].split(',')
ths=[float(x) for x in sys.argv[7].split(',')]
LIM=tuple(float(x) for x in sys.argv[8].split(',')) if len(sys.argv)>8 else None
res={t:[] for t in ths}
for f in frames:
    pr=load(f'{run}/{f}_pred.npy'); g=load(f'{run}/{f}_gt.npy')
    grng=[g[3*p] for p in range(H*W)]; glab=[g[3*p+2]>0.5 for p in range(H*W)]
    G=pts(grng,glab)
    prng=[min(max(pr[3*p],1e-6),1e9) for p in range(H*W)]
    for t in ths:
        P=pts(prng,[pr[3*p+2]>t and (LIM is None or LIM[0]<=prng[p]<=LIM[1]) for p in range(H*W)])
        d1=nn2(P,G); d2=nn2(G,P)
        a=sum(d1)/len(d1); b=sum(d2)/len(d2)
        prec=sum(1 for d in d1 if d<0.05)/len(d1); rec=sum(1 for d in d2 if d<0.05)/len(d2)
        f1=2*prec*rec/(prec+rec) if prec+rec>0 else 0
        res[t].append((a,b,f1,len(P),len(G)))
for t in ths:
    n=len(res[t]); m=[sum(x[i] for x in res[t])/n for i in range(5)]
    print(f'threshold {t}: CD {m[0]+m[1]:.4f} (pred->GT {m[0]:.4f}, GT->pred {m[1]:.4f}) F {m[2]:.4f} points {m[3]:.0f}/{m[4]:.0f}')
