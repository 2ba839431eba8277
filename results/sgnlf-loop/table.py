#!/usr/bin/env python3
"""Table of the loop runs: python3 table.py WORK_DIR > table.md (reads runs/<seq>-<row>/)."""
import json, os, sys

work = sys.argv[1]
rows = [("geonlf", "GeoNLF (hash grid, sequential graph)"),
        ("sequential", "SG-NLF w/o adversarial term, sequential graph only"),
        ("confidence", "SG-NLF w/o adversarial term, confidence-aware graph")]
print("| sequence | row | CD (m²) ↓ | F-score ↑ | depth RMSE (m) ↓ | depth PSNR ↑ | intensity PSNR ↑ "
      "| ATE (m) ↓ | RPE t (cm) / r (°) | non-adjacent edges (last graph) | train s |")
print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for seq in ("kitti360-loop", "nuscenes-loop"):
    for key, name in rows:
        run = os.path.join(work, "runs", f"{seq}-{key}")
        mpath = os.path.join(run, "metrics.json")
        if not os.path.exists(mpath):
            print(f"| {seq} | {name} | not run |||||||||")
            continue
        m = json.load(open(mpath))
        x, p = m["metrics"], m["pose_metrics"]
        s = json.load(open(os.path.join(run, "summary.json")))
        g = os.path.join(run, "pose_graph", "latest.json")
        edges = json.load(open(g))["non_adjacent_edges"] if os.path.exists(g) else "–"
        secs = s.get("train_seconds", s.get("seconds", ""))
        print(f"| {seq} | {name} | {x['cd']:.4f} | {x['fscore']:.4f} | {x['depth_rmse']:.3f} | "
              f"{x['depth_psnr']:.2f} | {x['intensity_psnr']:.2f} | **{p['ate_m']:.3f}** | "
              f"{p['rpe_t_cm']:.2f} / {p['rpe_r_deg']:.3f} | {edges} | "
              f"{secs if isinstance(secs, str) else round(secs)} |")
