#!/usr/bin/env python3
"""Per-frame position error of estimated trajectories against a reference, as an SVG.

Usage: frame_errors.py OUT.svg TITLE GT.kitti.txt LABEL=EST.kitti.txt [LABEL=EST.kitti.txt ...]

Each estimate is aligned to the reference by SE(3) (Horn's closed form on the positions, no
scale), as the ATE of the metrics is; the plot shows |p_est - p_gt| per frame after it and
the legend the ATE (RMS) of each. Pure Python: no numpy here.
"""
import math
import sys


def positions(path):
    out = []
    for line in open(path):
        v = [float(x) for x in line.split()]
        if len(v) == 12:
            out.append((v[3], v[7], v[11]))
    return out


def jacobi_max_eigvec(a):
    """Eigenvector of the largest eigenvalue of a symmetric 4x4 matrix (cyclic Jacobi)."""
    n = 4
    a = [row[:] for row in a]
    v = [[1.0 if i == j else 0.0 for j in range(n)] for i in range(n)]
    for _ in range(100):
        off = sum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j)
        if off < 1e-22:
            break
        for p in range(n):
            for q in range(p + 1, n):
                if abs(a[p][q]) < 1e-300:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * a[p][q])
                t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1))
                c = 1 / math.sqrt(t * t + 1)
                s = t * c
                for k in range(n):
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(n):
                    vkp, vkq = v[k][p], v[k][q]
                    v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    i = max(range(n), key=lambda k: a[k][k])
    return [v[k][i] for k in range(n)]


def align(est, gt):
    """Rotation R and translation t minimising sum |R est + t - gt|^2 (Horn 1987)."""
    n = len(est)
    ce = [sum(p[k] for p in est) / n for k in range(3)]
    cg = [sum(p[k] for p in gt) / n for k in range(3)]
    s = [[sum((e[i] - ce[i]) * (g[j] - cg[j]) for e, g in zip(est, gt)) for j in range(3)]
         for i in range(3)]
    (sxx, sxy, sxz), (syx, syy, syz), (szx, szy, szz) = s
    n4 = [[sxx + syy + szz, syz - szy, szx - sxz, sxy - syx],
          [syz - szy, sxx - syy - szz, sxy + syx, szx + sxz],
          [szx - sxz, sxy + syx, -sxx + syy - szz, syz + szy],
          [sxy - syx, szx + sxz, syz + szy, -sxx - syy + szz]]
    w, x, y, z = jacobi_max_eigvec(n4)
    r = [[w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
         [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
         [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z]]
    t = [cg[i] - sum(r[i][k] * ce[k] for k in range(3)) for i in range(3)]
    return r, t


def frame_errors(est, gt):
    r, t = align(est, gt)
    errs = []
    for e, g in zip(est, gt):
        q = [sum(r[i][k] * e[k] for k in range(3)) + t[i] for i in range(3)]
        errs.append(math.dist(q, g))
    return errs


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    out, title, gt_path = sys.argv[1:4]
    gt = positions(gt_path)
    series = []
    for arg in sys.argv[4:]:
        label, path = arg.split("=", 1)
        est = positions(path)
        if len(est) != len(gt):
            sys.exit(f"{path}: {len(est)} poses, the reference {gt_path} has {len(gt)}")
        e = frame_errors(est, gt)
        series.append((label, e, math.sqrt(sum(x * x for x in e) / len(e))))
    W, H, L, R, T, B = 640, 300, 56, 16, 30, 40
    ymax = max(max(e) for _, e, _ in series) * 1.05
    n = len(gt)
    X = lambda i: L + (W - L - R) * i / max(n - 1, 1)
    Y = lambda v: H - B - (H - T - B) * v / ymax
    colours = ["#999999", "#d95f02", "#1b9e77", "#7570b3"]
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="11">',
           f'<text x="{L}" y="16" font-size="12">{title}</text>',
           f'<line x1="{L}" y1="{H-B}" x2="{W-R}" y2="{H-B}" stroke="black"/>',
           f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H-B}" stroke="black"/>',
           f'<text x="{(W+L)/2}" y="{H-8}" text-anchor="middle">frame</text>',
           f'<text x="12" y="{(H-B+T)/2}" transform="rotate(-90 12 {(H-B+T)/2})" text-anchor="middle">position error after SE(3) alignment (m)</text>']
    for k in range(5):
        v = ymax * k / 4
        svg.append(f'<text x="{L-4}" y="{Y(v)+4:.1f}" text-anchor="end">{v:.2f}</text>')
    for i in range(0, n, 5):
        svg.append(f'<text x="{X(i):.1f}" y="{H-B+14}" text-anchor="middle">{i}</text>')
    for s, (label, e, ate) in enumerate(series):
        c = colours[s % len(colours)]
        pts = " ".join(f"{X(i):.1f},{Y(v):.1f}" for i, v in enumerate(e))
        svg.append(f'<polyline fill="none" stroke="{c}" stroke-width="1.5" points="{pts}"/>')
        svg.append(f'<text x="{W-R-4}" y="{T+14*s}" text-anchor="end" fill="{c}">{label}: ATE {ate:.3f} m</text>')
    svg.append("</svg>")
    open(out, "w").write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
