#!/usr/bin/env python3
"""Return-probability quality of rendered test views, in the top beams and the rest.

usage: return_bce.py RENDER_DIR [RENDER_DIR ...]
RENDER_DIR: the output of `sgnlf render --renderer protocol` (<frame>_pred.npy, <frame>_gt.npy,
as far_returns.py reads them). Per folder, pooled over its frames, for the top 16 beams (rows
0-15) and the other rows: the ground truth's return rate and its entropy (the BCE of the best
constant), the prediction's BCE against the ground-truth labels (probabilities clipped to
[1e-6, 1 - 1e-6]), and its wrong decisions at 0.5 (missed and false returns).
"""
import glob
import math
import sys

from far_returns import load


def entropy(p):
    return 0.0 if p <= 0.0 or p >= 1.0 else -(p * math.log(p) + (1 - p) * math.log(1 - p))


def main(folders):
    for folder in folders:
        acc = {}
        for gp in sorted(glob.glob(folder + '/*_gt.npy')):
            h, w, g = load(gp)
            _, _, p = load(gp.replace('_gt.npy', '_pred.npy'))
            for i in range(h * w):
                a = acc.setdefault('top 16 beams' if i // w < 16 else 'other beams',
                                   [0, 0.0, 0.0, 0, 0])
                y = g[3 * i + 2] > 0.5
                q = min(max(p[3 * i + 2], 1e-6), 1 - 1e-6)
                a[0] += 1
                a[1] += -math.log(q) if y else -math.log(1 - q)
                a[2] += y
                a[3] += y and q <= 0.5
                a[4] += (not y) and q > 0.5
        print(folder)
        for k in ('top 16 beams', 'other beams'):
            n, bce, ys, missed, false = acc[k]
            print(f'  {k:12s} {n:6d} px  return rate {ys / n:.3f}  entropy {entropy(ys / n):.4f}'
                  f'  BCE {bce / n:.4f}  missed {missed:5d}  false {false:5d}')


if __name__ == '__main__':
    main(sys.argv[1:])
