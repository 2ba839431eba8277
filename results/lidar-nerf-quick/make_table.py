#!/usr/bin/env python3
"""Collects the run folders of the lidar-nerf quick runs (metrics.json, summary.json, run.json)
into OUT_DIR/results.json and OUT_DIR/table.md. Usage: make_table.py OUT_DIR RUN_DIR..."""
import json, os, sys

KEYS = ["cd", "fscore", "depth_rmse", "depth_medae", "depth_psnr", "depth_ssim", "depth_delta1",
        "intensity_rmse", "intensity_psnr", "raydrop_acc", "raydrop_f1"]
BETTER_LOW = {"cd", "depth_rmse", "depth_medae", "intensity_rmse"}
here = sys.argv[1]
os.makedirs(here, exist_ok=True)
runs = []
for d in sys.argv[2:]:
    m = json.load(open(os.path.join(d, "metrics.json")))
    s = json.load(open(os.path.join(d, "summary.json")))
    r = json.load(open(os.path.join(d, "run.json")))
    runs.append({"sequence": m["dataset"], "seed": r["seed"], "step": m["step"],
                 "train_seconds": s["train_seconds"], "samples_per_s": s["samples_per_s"],
                 "steps_per_s": s["steps_per_s"], "device": s["device"],
                 "model": m["metrics"], "naive": m["naive_baseline"]["metrics"],
                 "model_per_frame": m["per_frame"], "naive_per_frame": m["naive_baseline"]["per_frame"],
                 "config": r["config"], "config_hash": r["config_hash"]})

def mean(rows, key):
    v = [x[key] for x in rows if x.get(key) is not None]
    return sum(v) / len(v) if len(v) == len(rows) and v else None

avg_model = {k: mean([r["model"] for r in runs], k) for k in KEYS}
avg_naive = {k: mean([r["naive"] for r in runs], k) for k in KEYS}
json.dump({"method": "lidar-nerf", "preset": "quick", "runs": runs,
           "mean_over_sequences": {"model": avg_model, "naive_baseline": avg_naive}},
          open(os.path.join(here, "results.json"), "w"), indent=2)

def f(v):
    return "null" if v is None else f"{v:.4f}"

lines = ["| sequence | method | " + " | ".join(KEYS) + " | train s |", "|---|---|" + "---|" * (len(KEYS) + 1)]
for r in runs:
    lines.append(f"| {r['sequence']} | lidar-nerf quick | " + " | ".join(f(r["model"].get(k)) for k in KEYS) + f" | {r['train_seconds']:.0f} |")
    lines.append(f"| {r['sequence']} | naive baseline | " + " | ".join(f(r["naive"].get(k)) for k in KEYS) + " | – |")
lines.append("| **mean** | **lidar-nerf quick** | " + " | ".join(f(avg_model[k]) for k in KEYS) + " | |")
lines.append("| **mean** | **naive baseline** | " + " | ".join(f(avg_naive[k]) for k in KEYS) + " | |")
wins = [k for k in ["cd", "fscore", "depth_rmse"] if avg_model[k] is not None and avg_naive[k] is not None
        and ((avg_model[k] < avg_naive[k]) if k in BETTER_LOW else (avg_model[k] > avg_naive[k]))]
open(os.path.join(here, "table.md"), "w").write("\n".join(lines) + "\n\nBeats the naive baseline (mean) on: "
                                                 + (", ".join(wins) if wins else "none of cd, fscore, depth_rmse") + "\n")
print("\n".join(lines))
print("wins:", wins)
