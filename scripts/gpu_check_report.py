#!/usr/bin/env python3
"""Assembles scripts/gpu-check.sh's one JSON from its work folder (GPU_CHECK_WORK): parts.tsv
(name, rc, seconds, log, note per part), devices.json (`sgnlf devices --json`), bench/*.json
(Google Benchmark, aggregates only) and train/*.summary.json (`sgnlf train`'s summaries).
Writes the JSON to stdout. The layout is described in docs/gpu-check.md."""
import glob
import json
import os
import socket
import subprocess
import sys
import time

work = os.environ["GPU_CHECK_WORK"]


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError) as e:
        print(f"gpu_check_report: {path}: {e}", file=sys.stderr)
        return None


def parts():
    rows = []
    with open(os.path.join(work, "parts.tsv")) as f:
        for line in f:
            name, rc, secs, log, note = (line.rstrip("\n").split("\t") + [""] * 5)[:5]
            row = {"name": name, "rc": int(rc) if rc.lstrip("-").isdigit() else rc,
                   "seconds": float(secs) if secs else None}
            if rc in ("124", "137"):
                row["timed_out"] = True
            if log:
                row["log"] = log
            if note:
                row["note"] = note
            rows.append(row)
    return rows


def device():
    devices = load(os.path.join(work, "devices.json")) if os.path.exists(
        os.path.join(work, "devices.json")) else None
    if not devices:
        return None, None, devices
    sel = next((d for d in devices if d.get("selected")), None)
    if sel is None:
        return None, None, devices
    keys = ["platform", "platform_version", "name", "vendor", "type", "version",
            "driver_version", "opencl_c_version", "compute_units", "clock_mhz",
            "global_mem_bytes", "max_work_group_size"]
    return {k: sel.get(k) for k in keys}, sel.get("device_profile"), devices


# Google Benchmark's own keys of a run; every other numeric key is a user counter.
STANDARD = {"name", "family_index", "per_family_instance_index", "run_name", "run_type",
            "repetitions", "repetition_index", "threads", "aggregate_name", "aggregate_unit",
            "iterations", "real_time", "cpu_time", "time_unit", "label", "error_occurred",
            "error_message"}


def benchmarks():
    out = {}
    for path in sorted(glob.glob(os.path.join(work, "bench", "*.json"))):
        j = load(path)
        if j is None:
            continue
        rows = []
        for b in j.get("benchmarks", []):
            if b.get("error_occurred"):
                rows.append({"name": b.get("run_name", b.get("name")),
                             "error": b.get("error_message", "")})
                continue
            if b.get("aggregate_name", "median") != "median":
                continue
            row = {"name": b.get("run_name", b.get("name")), "median_real_time": b.get("real_time"),
                   "time_unit": b.get("time_unit"), "repetitions": b.get("repetitions", 1)}
            counters = {k: v for k, v in b.items() if k not in STANDARD and isinstance(v, (int, float))}
            if counters:
                row["counters"] = counters
            if b.get("label"):
                row["label"] = b["label"]
            rows.append(row)
        out[os.path.basename(path)[:-5]] = rows
    return out


def training(ran_parts):
    out = {}
    steps = int(os.environ.get("GPU_CHECK_STEPS", "0"))
    for m in os.environ.get("GPU_CHECK_METHODS", "").split():
        if "train_" + m not in ran_parts:
            continue
        s = load(os.path.join(work, "train", m + ".summary.json")) if os.path.exists(
            os.path.join(work, "train", m + ".summary.json")) else None
        if s is None:
            out[m] = None
            continue
        ran = s.get("end_step", 0) - s.get("start_step", 0)
        train_s = s.get("train_seconds")
        geo = s.get("geometric_seconds", 0.0)
        row = {"steps_asked": steps, "steps": ran, "preset": os.environ.get("GPU_CHECK_PRESET"),
               "train_seconds": train_s, "load_seconds": s.get("load_seconds"),
               "steps_per_s": s.get("steps_per_s"), "samples_per_s": s.get("samples_per_s"),
               "parameters": s.get("parameters"), "device": s.get("device")}
        for k in ("geometric_seconds", "spectral_seconds", "consistency_seconds"):
            if k in s:
                row[k] = s[k]
        # The field steps alone: without the geometric stage (host work before the epochs).
        if train_s and ran > 0 and train_s - geo > 0:
            row["steps_per_s_without_geometric"] = ran / (train_s - geo)
        # Steady state: between the first logged step (after the program builds and the first
        # step's allocations) and the last (before the final checkpoint is written).
        log = os.path.join(work, "train", m + ".train_log.jsonl")
        if os.path.exists(log):
            with open(log) as f:
                lines = [json.loads(x) for x in f if x.strip()]
            if len(lines) >= 2 and lines[-1]["elapsed_s"] > lines[0]["elapsed_s"]:
                row["steady_steps_per_s"] = (lines[-1]["step"] - lines[0]["step"]) / (
                    lines[-1]["elapsed_s"] - lines[0]["elapsed_s"])
                row["steady_steps"] = [lines[0]["step"], lines[-1]["step"]]
        out[m] = row
    return out


def git_sha():
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True,
                              timeout=10).stdout.strip() or None
    except (OSError, subprocess.SubprocessError):
        return None


p = parts()
dev, profile, devices = device()
report = {
    "schema": "sgnlf-gpu-check/1",
    "date": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    "host": socket.gethostname(),
    "git_sha": git_sha(),
    "build_dir": os.environ.get("GPU_CHECK_BUILD"),
    "device": dev,
    "device_profile": profile,
    "env": {k: os.environ.get(k) for k in ("SGNLF_DEVICE", "SGNLF_DEVICE_PROFILE",
                                           "OCL_ICD_VENDORS", "LD_LIBRARY_PATH")},
    "ok": all(r["rc"] in (0, "skipped") for r in p),
    "failed_parts": [r["name"] for r in p if r["rc"] not in (0, "skipped")],
    "total_seconds": int(os.environ.get("GPU_CHECK_TOTAL", "0")),
    "parts": p,
    "benchmarks": benchmarks(),
    "training": training({r["name"] for r in p}),
    "devices": devices,
}
json.dump(report, sys.stdout, indent=1)
print()
