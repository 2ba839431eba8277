#!/usr/bin/env python3
"""Time-to-quality from two run folders trained side by side (run.sh): the target is what the
first (the published sampler) reaches at its last evaluation, F-score (higher is better) and
depth RMSE (lower is better); for each run, the training seconds (evaluations excluded) of the
first evaluation at which both are reached, and its throughput from train_log.jsonl."""
import json, sys


def read_jsonl(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def summary(run):
    evals = read_jsonl(f"{run}/eval_log.jsonl")
    train = read_jsonl(f"{run}/train_log.jsonl")
    return evals, train


def main():
    base_dir, fast_dir = sys.argv[1], sys.argv[2]
    base, base_train = summary(base_dir)
    fast, fast_train = summary(fast_dir)
    target = base[-1]["metrics"]
    f_t, r_t = target["fscore"], target["depth_rmse"]
    print(f"target (the published sampler's last evaluation, step {base[-1]['step']}): "
          f"F-score {f_t:.4f}, depth RMSE {r_t:.3f} m\n")
    print("| run | steps to target | train s to target | train s, whole run | final F-score | final depth RMSE | final CD | live fraction | coarse fraction |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    times = {}
    for name, ev, tr in (("published sampler", base, base_train), ("fast sampler", fast, fast_train)):
        hit = next((e for e in ev if e["metrics"]["fscore"] >= f_t and e["metrics"]["depth_rmse"] <= r_t), None)
        last = ev[-1]
        live = [l["live_fraction"] for l in tr if "live_fraction" in l]
        coarse = [l["coarse_fraction"] for l in tr if "coarse_fraction" in l]
        mean = lambda v: sum(v) / len(v) if v else float("nan")
        times[name] = hit["train_seconds"] if hit else None
        to = f"{hit['step']} | {hit['train_seconds']:.0f}" if hit else "not reached | –"
        print(f"| {name} | {to} | {last['train_seconds']:.0f} | {last['metrics']['fscore']:.4f} | "
              f"{last['metrics']['depth_rmse']:.3f} | {last['metrics']['cd']:.4f} | "
              f"{mean(live):.3f} | {mean(coarse) if coarse else 1.0:.3f} |")
    if times["published sampler"] and times["fast sampler"]:
        print(f"\ntime-to-quality ratio (fast / published): "
              f"{times['fast sampler'] / times['published sampler']:.3f}")
    pose = "pose" in base[-1]["metrics"]
    if pose:  # the pose-free methods: the trajectory too
        print("\nATE at the last evaluation (m): published sampler "
              f"{base[-1]['metrics']['pose']['ate_m']:.4f}, fast sampler {fast[-1]['metrics']['pose']['ate_m']:.4f}")
    print("\nper evaluation (step: F-score / depth RMSE" + (" / ATE" if pose else "") + " / train s)")
    for name, ev in (("published", base), ("fast", fast)):
        print(name + ": " + ", ".join(
            f"{e['step']}: {e['metrics']['fscore']:.4f}/{e['metrics']['depth_rmse']:.3f}"
            + (f"/{e['metrics']['pose']['ate_m']:.3f}" if pose else "") + f"/{e['train_seconds']:.0f}"
            for e in ev))


if __name__ == "__main__":
    main()
