#!/usr/bin/env python3
"""Run-to-run spread of a trained table across training seeds, beside the loose tolerances.

usage: spread.py TABLES_JSON RESULTS_JSON [RESULTS_JSON ...] > spread.md
       spread.py --json TABLES_JSON RESULTS_JSON [...] > spread.json

Every RESULTS_JSON is one `sgnlf bench` run of the same table, scale, rows and sequences with
another --seed (the data and the pose noise are seeded apart from --seed, so only the training's
randomness differs). For every row, sequence (and the row's mean) and metric it reports the
mean, the sample standard deviation, the range, and the loose tolerance of
runtime/harness/tables.json evaluated at the first run's value (abs + rel * |base|, the
allowance `sgnlf compare` gives in the metric's worse direction), as a multiple of the standard
deviation; and whether comparing every other seed against the first seed's run passes loose.
Pure Python (no numpy).
"""
import json
import math
import sys


def load(path):
    with open(path) as f:
        return json.load(f)


def sd(xs):
    if len(xs) < 2:
        return float("nan")
    m = sum(xs) / len(xs)
    return math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1))


def metric_values(row):
    """{(sequence or 'mean'): {metric: value}} of one row."""
    out = {}
    for s in row.get("sequences", []):
        m = dict(s.get("metrics") or {})
        m.update(s.get("pose_metrics") or {})
        out[s["sequence"]] = {k: v for k, v in m.items() if isinstance(v, (int, float))}
    out["mean"] = {k: v for k, v in (row.get("mean") or {}).items() if isinstance(v, (int, float))}
    return out


def main(argv):
    as_json = False
    if argv and argv[0] == "--json":
        as_json, argv = True, argv[1:]
    if len(argv) < 3:
        sys.exit(__doc__)
    tables = load(argv[0])
    loose = tables["tolerances"]["loose"]
    infos = tables["metrics"]
    runs = [load(p) for p in argv[1:]]
    seeds = [r["config"]["seed"] for r in runs]
    metrics = [k for k in infos if k not in ("frames",)]
    def stamp(g):
        return g["sha"][:7] + ("-dirty" if g.get("dirty") else "") if g else "?"
    report = {"seeds": seeds, "runs": argv[1:],
              "git": [stamp(r["context"].get("git")) for r in runs],
              "build_git": [stamp(r["context"].get("build", {}).get("git")) for r in runs],
              "rows": []}
    for ri, row0 in enumerate(runs[0]["rows"]):
        if row0.get("status", "ok") not in ("ok", None) and not row0.get("sequences"):
            continue
        per_run = [metric_values(r["rows"][ri]) for r in runs]
        for where in per_run[0]:
            for k in metrics:
                xs = [pr.get(where, {}).get(k) for pr in per_run]
                if any(x is None for x in xs):
                    continue
                tol_spec = loose.get(k, loose["default"])
                base = xs[0]
                tol = tol_spec["abs"] + tol_spec["rel"] * abs(base)
                lower = infos[k]["better"] == "lower"
                worse = [(x - base) if lower else (base - x) for x in xs[1:]]
                s = sd(xs)
                report["rows"].append({
                    "method": row0["method"], "where": where, "metric": k, "values": xs,
                    "mean": sum(xs) / len(xs), "sd": s, "min": min(xs), "max": max(xs),
                    "loose_tol_at_seed0": tol,
                    "tol_over_sd": tol / s if s > 0 else float("inf"),
                    "max_worse_vs_seed0": max(worse) if worse else float("nan"),
                    "loose_passes": all(w <= tol for w in worse)})
    if as_json:
        json.dump(report, sys.stdout, indent=1, allow_nan=True)
        print()
        return
    print(f"seeds {seeds}; source trees at the start {report['git']}; binaries built from "
          f"{report['build_git']}\n")
    print("| row | sequence | metric | mean | sd | min | max | loose tol at seed " +
          f"{seeds[0]} | tol / sd | worst seed vs seed {seeds[0]} | loose passes |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|")
    for e in report["rows"]:
        d = infos[e["metric"]].get("digits", 4) + 1
        f = lambda v: f"{v:.{d}f}"
        print(f"| {e['method']} | {e['where']} | {e['metric']} | {f(e['mean'])} | {f(e['sd'])} | "
              f"{f(e['min'])} | {f(e['max'])} | {f(e['loose_tol_at_seed0'])} | "
              f"{e['tol_over_sd']:.1f} | {f(e['max_worse_vs_seed0'])} | "
              f"{'yes' if e['loose_passes'] else '**no**'} |")


if __name__ == "__main__":
    main(sys.argv[1:])
