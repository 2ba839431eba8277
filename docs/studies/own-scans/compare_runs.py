#!/usr/bin/env python3
"""Largest difference between KITTI trajectory files (translation in metres, rotation entries),
each file against the first: e.g. the three reconstruct runs' odometry and optimised poses, or
a run's odometry against `sgnlf odometry` on the genuine layout.

    python3 compare_runs.py A.kitti.txt B.kitti.txt [C.kitti.txt ...]
"""
import sys


def read(path):
    rows = []
    for k, line in enumerate(open(path), 1):
        v = [float(x) for x in line.split()]
        if len(v) != 12:
            raise SystemExit(f"{path}:{k}: expected 12 numbers, got {len(v)}")
        rows.append(v)
    return rows


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    ref = read(sys.argv[1])
    worst = 0.0
    for path in sys.argv[2:]:
        other = read(path)
        if len(other) != len(ref):
            raise SystemExit(f"{path}: {len(other)} poses, {sys.argv[1]} has {len(ref)}")
        dt = max(max(abs(a[i] - b[i]) for i in (3, 7, 11)) for a, b in zip(ref, other))
        dr = max(max(abs(a[i] - b[i]) for i in (0, 1, 2, 4, 5, 6, 8, 9, 10)) for a, b in zip(ref, other))
        worst = max(worst, dt)
        print(f"{path}: {len(other)} poses, max |dt| {dt:.3e} m, max |dR| {dr:.3e}")
    print(f"largest translation difference {worst:.3e} m ({'within' if worst <= 1e-3 else 'ABOVE'} 1 mm)")


if __name__ == "__main__":
    main()
