#!/usr/bin/env python3
"""Wrong return decisions of rendered test views by range (no numpy needed).

usage: far_returns.py RENDER_DIR [RENDER_DIR ...]
RENDER_DIR: the output of `sgnlf render --renderer protocol` (<frame>_pred.npy, <frame>_gt.npy:
H x W x 3 float32, range / intensity / ray_drop). Prints, per folder and pooled over its frames,
the missed returns (ground truth returns, predicted probability <= 0.5) and false returns
(predicted > 0.5, ground truth dropped) below and above 50 m (the ground truth's range for a
missed return, the prediction's for a false one), with their share of the depth MSE
(clipped to 80 m, divided by all pixels, as depth_mse_missed / depth_mse_false).
"""
import array
import glob
import sys


def load(path):
    b = open(path, 'rb').read()
    hl = b[8] | (b[9] << 8)
    head = b[10:10 + hl].decode()
    shape = head.split("'shape': (")[1].split(')')[0]
    h, w, c = [int(x) for x in shape.split(',') if x.strip()]
    a = array.array('f')
    a.frombytes(b[10 + hl:])
    assert c == 3 and len(a) == h * w * 3, path
    return h, w, a


def clip(r):
    return min(max(r, 1e-6), 80.0)


def main(folders):
    for folder in folders:
        n = 0
        stats = {k: [0, 0.0] for k in ('missed<50', 'missed>=50', 'false<50', 'false>=50')}
        for gp in sorted(glob.glob(folder + '/*_gt.npy')):
            h, w, g = load(gp)
            _, _, p = load(gp.replace('_gt.npy', '_pred.npy'))
            n += h * w
            for i in range(h * w):
                truth, hit = g[3 * i + 2] > 0.5, p[3 * i + 2] > 0.5
                if truth and not hit:
                    r = g[3 * i]
                    key = 'missed<50' if r < 50 else 'missed>=50'
                    err = clip(r) - 1e-6
                elif hit and not truth:
                    r = p[3 * i]
                    key = 'false<50' if r < 50 else 'false>=50'
                    err = clip(r) - 1e-6
                else:
                    continue
                stats[key][0] += 1
                stats[key][1] += err * err
        print(folder, f'{n} pixels')
        for k, (count, se) in stats.items():
            print(f'  {k:11s} {count:6d} pixels  MSE share {se / n:.3f} m^2')


if __name__ == '__main__':
    main(sys.argv[1:])
