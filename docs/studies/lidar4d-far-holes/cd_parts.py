#!/usr/bin/env python3
"""Where a rendered view's CD ground truth -> prediction comes from (no numpy needed).

usage: cd_parts.py RENDER_DIR [RENDER_DIR ...]
RENDER_DIR: the output of `sgnlf render --renderer protocol` (<frame>_pred.npy, <frame>_gt.npy,
as ../lidar4d-depth-error/far_returns.py reads them). Both range images become points with the
KITTI-360 twin's beam layout (66 rows spread evenly from +2 deg down over 26.9 deg, 1030
columns over 360 deg); every ground-truth point's squared distance to the nearest predicted
point is summed by case (the prediction returns there too, or drops it: "missed") and by the
ground truth's range (below / from 50 m), divided by the number of ground-truth points. The
parts sum to the frame's cd_gt_to_pred (up to the beam layout's rounding).
"""
import glob
import math
import os
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'lidar4d-depth-error'))
from far_returns import load
FOV_UP, FOV = 2.0, 26.9
def pts(img, h, w):
    out = []
    for i in range(h * w):
        if img[3*i+2] > 0.5 and img[3*i] > 0:
            r, c = divmod(i, w)
            el = math.radians(FOV_UP - FOV * r / (h - 1)); az = math.pi - 2 * math.pi * (c + 0.5) / w
            d = img[3*i]
            out.append((i, d * math.cos(el) * math.cos(az), d * math.cos(el) * math.sin(az), d * math.sin(el), d))
    return out
def grid(P, s):
    g = {}
    for p in P: g.setdefault((int(p[1]//s), int(p[2]//s), int(p[3]//s)), []).append(p)
    return g
def nn2(g, s, q):
    k = (int(q[1]//s), int(q[2]//s), int(q[3]//s)); best = 1e18; rad = 0
    while True:
        for dx in range(-rad, rad+1):
            for dy in range(-rad, rad+1):
                for dz in range(-rad, rad+1):
                    if max(abs(dx),abs(dy),abs(dz)) != rad: continue
                    for p in g.get((k[0]+dx, k[1]+dy, k[2]+dz), ()):
                        d = (p[1]-q[1])**2 + (p[2]-q[2])**2 + (p[3]-q[3])**2
                        if d < best: best = d
        if best < 1e18 and (rad * s) ** 2 >= best: return best
        rad += 1
        if rad > 60: return best
for folder in sys.argv[1:]:
    for gp in sorted(glob.glob(folder + '/*_gt.npy')):
        h, w, G = load(gp); _, _, Pd = load(gp.replace('_gt', '_pred'))
        gt, pr = pts(G, h, w), pts(Pd, h, w)
        s = 1.0; g = grid(pr, s)
        predret = set(p[0] for p in pr)
        acc = {}
        for q in gt:
            d2 = nn2(g, s, q)
            case = ('both' if q[0] in predret else 'missed') + (' >=50m' if q[4] >= 50 else ' <50m')
            a = acc.setdefault(case, [0, 0.0]); a[0] += 1; a[1] += d2
        n = len(gt)
        print(folder, gp.split('/')[-1][:2], 'GT pts', n, ' '.join('%s: %d pts, %.4f' % (k, v[0], v[1] / n) for k, v in sorted(acc.items())))
