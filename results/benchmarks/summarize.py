#!/usr/bin/env python3
"""Markdown table of Google Benchmark JSON files written by scripts/bench.sh.

Usage: python3 results/benchmarks/summarize.py runs/bench/*.json > table.md
Keeps the median aggregate when repetitions were run (else the single run) and prints every
numeric counter (throughputs, GFLOP/s or GB/s and frac_peak against the roofline that the same
process measured). Python standard library only.
"""
import json
import sys

SKIP = {"name", "run_name", "run_type", "repetitions", "repetition_index", "threads",
        "iterations", "real_time", "cpu_time", "time_unit", "family_index",
        "per_family_instance_index", "aggregate_name", "aggregate_unit"}


def rows(path):
    with open(path) as f:
        j = json.load(f)
    ctx = j.get("context", {})
    head = "## %s (git %s%s, device %s)" % (
        path.rsplit("/", 1)[-1], ctx.get("sgnlf.git.sha", "?")[:10],
        " dirty" if ctx.get("sgnlf.git.dirty") == "true" else "",
        ctx.get("sgnlf.opencl.device", "?"))
    out = [head, "", "| benchmark | time | counters |", "|---|---:|---|"]
    for b in j["benchmarks"]:
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        counters = ", ".join("%s %.4g" % (k, v) for k, v in b.items()
                             if k not in SKIP and isinstance(v, (int, float)))
        out.append("| %s | %.3f %s | %s |" % (b["name"], b["real_time"], b["time_unit"], counters))
    return out + [""]


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: summarize.py BENCH.json [...]")
    for p in sys.argv[1:]:
        print("\n".join(rows(p)))
