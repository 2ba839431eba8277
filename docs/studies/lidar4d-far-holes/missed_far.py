#!/usr/bin/env python3
"""Far ground-truth returns a rendering drops: is it the geometry or the ray-drop decision?

usage: missed_far.py RENDER_DIR [RENDER_DIR ...]
RENDER_DIR: the output of `sgnlf render --renderer protocol` (test frames) or of
`sgnlf render --renderer protocol --frames IDS` (any recorded frames). For every frame, the
pixels where the ground truth returns at >= 50 m and the prediction drops (return probability
<= 0.5): how many, how many of them have a predicted range within 2 m of the ground truth (the
geometry is there, the decision drops it), the mean |range error| and the mean probability.
"""
import glob
import os
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'lidar4d-depth-error'))
from far_returns import load

for d in sys.argv[1:]:
    stems = sorted((p[:-len('_gt.npy')] for p in glob.glob(os.path.join(d, '*_gt.npy'))),
                   key=lambda s: int(os.path.basename(s)))
    for stem in stems:
        h, w, g = load(stem + '_gt.npy')
        _, _, p = load(stem + '_pred.npy')
        miss = [(g[3*i], p[3*i], p[3*i+2]) for i in range(h * w)
                if g[3*i+2] > 0.5 and g[3*i] >= 50 and p[3*i+2] <= 0.5]
        n = len(miss)
        if not n:
            print(d, os.path.basename(stem), 'missed far 0')
            continue
        print(d, os.path.basename(stem), 'missed far', n,
              'range within 2 m', sum(1 for m in miss if abs(m[0] - m[1]) < 2),
              'mean |range error| %.1f m' % (sum(abs(m[0] - m[1]) for m in miss) / n),
              'mean probability %.2f' % (sum(m[2] for m in miss) / n))
