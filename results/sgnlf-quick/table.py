#!/usr/bin/env python3
"""SG-NLF beside GeoNLF at quick: python3 table.py WORK_DIR > table.md.
Reads WORK_DIR/quick-<table>-<row>/results.json (run.sh), else the committed whole table
results/quick-<table>/results.json; a row in neither prints "not run"."""
import json, os, sys

work = sys.argv[1]
COLS = [("cd", "CD (m²) ↓", 4), ("fscore", "F-score ↑", 4), ("depth_rmse", "depth RMSE (m) ↓", 3),
        ("intensity_rmse", "intensity RMSE ↓", 4), ("ate_m", "ATE (m) ↓", 3),
        ("rpe_t_cm", "RPE t (cm) ↓", 2), ("rpe_r_deg", "RPE r (°) ↓", 3)]


HERE = os.path.dirname(os.path.abspath(__file__))


def row(table, method):
    """The row from run.sh's output, else from the committed whole quick table (older binary)."""
    for p in (os.path.join(work, f"quick-{table}-{method.replace('-', '')}", "results.json"),
              os.path.join(HERE, "..", f"quick-{table}", "results.json")):
        if os.path.exists(p):
            r = json.load(open(p))
            x = next((x for x in r["rows"] if x["method"] == method), None)
            if x is not None and x["status"] == "ok":
                break
    else:
        return None, None
    return x, r["context"]["git"]["sha"][:7]


for table in ("kitti360-low", "nuscenes-low"):
    print(f"\n### {table}, quick, seed 1\n")
    print("| row | sequence | " + " | ".join(c[1] for c in COLS) + " | train s | tree at run |")
    print("|---|---|" + "---:|" * (len(COLS) + 1) + "---|")
    means = {}
    for method, label in (("geonlf", "GeoNLF"), ("sg-nlf", "SG-NLF")):
        x, sha = row(table, method)
        if x is None or x["status"] != "ok":
            print(f"| {label} | not run |" + " |" * (len(COLS) + 2))
            continue
        for s in x["sequences"] + [None]:
            m = x["mean"] if s is None else {**s["metrics"], **(s["pose_metrics"] or {})}
            cells = [f"{m[k]:.{d}f}" if m.get(k) is not None else "—" for k, _, d in COLS]
            secs = "" if s is None else f"{s['timings']['train']:.0f}"
            name = "**mean**" if s is None else s["sequence"]
            print(f"| {label} | {name} | " + " | ".join(cells) + f" | {secs} | {sha} |")
        means[method] = x["mean"]
    print("\n*tree at run*: `context.git.sha`, the source tree's HEAD when the run started "
          "(results/schema.md), not necessarily the binary's commit: see README.md.")
    if len(means) == 2:
        g, o = means["geonlf"], means["sg-nlf"]
        print("\nSG-NLF against GeoNLF (means): " + ", ".join(
            f"{k} {100 * (o[k] - g[k]) / g[k]:+.1f} %" for k in ("cd", "ate_m", "depth_rmse")
            if g.get(k) and o.get(k) is not None) + " (paper: CD −35.8 %, ATE −68.8 % on nuScenes).")
