#!/usr/bin/env python3
"""Wrong return decisions in the top 16 beams at 0.5 and at the best threshold (a diagnostic:
the threshold is chosen on the test views themselves, 0.005 to 0.995 in steps of 0.005).

usage: best_threshold.py RENDER_DIR [RENDER_DIR ...]   (folders as far_returns.py reads them)
If a method's wrong decisions fall much at another threshold, its return probability is
miscalibrated; if not, it lacks the information.
"""
import bisect
import glob
import sys

from far_returns import load


def main(folders):
    for folder in folders:
        pos, neg = [], []
        for gp in sorted(glob.glob(folder + '/*_gt.npy')):
            h, w, g = load(gp)
            _, _, p = load(gp.replace('_gt.npy', '_pred.npy'))
            for i in range(16 * w):
                (pos if g[3 * i + 2] > 0.5 else neg).append(p[3 * i + 2])
        pos.sort()
        neg.sort()

        def wrong(t):
            return bisect.bisect_right(pos, t) + len(neg) - bisect.bisect_right(neg, t)

        best = min((wrong(k / 200), k / 200) for k in range(1, 200))
        print(f'{folder}: top 16 beams, wrong at 0.5: {wrong(0.5)}, '
              f'at the best threshold {best[1]:.3f}: {best[0]}')


if __name__ == '__main__':
    main(sys.argv[1:])
