#!/usr/bin/env python3
"""Config shape 2: the modules' own configs embedded, presence the only switch (issue 55 item 4).

Rewrites the resolved training configs recorded in committed results (results/tables/*/*/
results.json, every run of every row) from the old shape to the new one, value for value:

  field.{levels, features_per_level, log2_table_size, base_resolution, per_level_scale}
      -> field.grid (field::HashGridConfig, every key: deterministic true, half_table false,
         schedule "auto" were the values the old copy fixed)
  optim.{beta1, beta2, eps} -> optim.adam (field::AdamConfig; weight_decay 0, the value used)
  geometric.{points_per_frame, edge_offsets, tau_scale, lr_rot, lr_trans, residual, seed,
      threads} -> geometric.optimizer (posegraph::GeometricConfig, every key but the per-call
      steps: min_distance 0.15 and the normals' defaults were the values used)
  a section with "enabled": false (spectral, pose_graph, consistency, reweight, geometric,
      lidar4d.flow, lidar4d.refine) -> the section removed; "enabled": true -> the key removed;
      geometric beside pose_optim.optimize false (the stage was never built) -> removed.

The floats the modules hold as float (the grid's resolution and scale, Adam's β and ε) are
written as the build writes them: the float's value. Before it rewrites a run the script checks
that the recorded config hashes to the recorded config_hash (FNV-1a 64 of the compact JSON with
the thread counts at 2, as TrainConfig::hash), so it migrates exactly the hashed content; a run
that does not is refused. It does not compute the new hashes: this build does, with
  SGNLF_WRITE_COMMITTED_CONFIG_HASHES=1 build/tests/pipeline/test_pipeline_config "[committed-configs]"
(which also reformats the files as the harness writes them), and then
  sgnlf merge --out results/tables/T/S results/tables/T/S/results.json
refreshes each table's current hashes and stale flags. The test without the variable checks
that every committed run's hash is its config's and that the current rows' configs are exactly
what this build resolves. Usage: python3 scripts/migrations/config_shape_2.py [results.json ...]
"""
import copy
import glob
import json
import struct
import sys


def f32(x):
    return struct.unpack("f", struct.pack("f", float(x)))[0]


def fnv1a64(text):
    h = 1469598103934665603
    for b in text.encode("utf-8"):
        h = ((h ^ b) * 1099511628211) & 0xFFFFFFFFFFFFFFFF
    return "%016x" % h


def dump(j):
    return json.dumps(j, sort_keys=True, separators=(",", ":"), ensure_ascii=False)


def old_hash(cfg):
    c = copy.deepcopy(cfg)
    g = c.get("geometric")
    if isinstance(g, dict) and "threads" in g:  # written only when not 2
        g.pop("threads")
    if isinstance(c.get("pose_graph"), dict) and "threads" in c["pose_graph"]:
        c["pose_graph"]["threads"] = 2
    return fnv1a64(dump(c))


def switch(section, where):
    """None when the section was off, else the section without its 'enabled' key."""
    if not isinstance(section, dict):
        raise SystemExit(f"{where}: not an object")
    s = dict(section)
    on = s.pop("enabled", True)
    return s if on else None


def reshape(cfg, resolved=True):
    """The config in shape 2. resolved=False: a preset or overrides (only the keys given move,
    and floats keep their text)."""
    c = copy.deepcopy(cfg)
    num = f32 if resolved else (lambda x: x)
    f = c.get("field")
    if isinstance(f, dict):
        moved = {"levels": "levels", "features_per_level": "features",
                 "log2_table_size": "log2_table_size", "base_resolution": "base_resolution",
                 "per_level_scale": "per_level_scale"}
        grid = {}
        for old, new in moved.items():
            if old in f:
                v = f.pop(old)
                grid[new] = num(v) if new in ("base_resolution", "per_level_scale") else v
        if resolved:
            grid.update({"deterministic": True, "half_table": False, "schedule": "auto"})
            if "base_resolution" in grid:
                grid["base_resolution"] = f32(grid["base_resolution"])
        if grid:
            f["grid"] = grid
    o = c.get("optim")
    if isinstance(o, dict):
        adam = {k: num(o.pop(k)) for k in ("beta1", "beta2", "eps") if k in o}
        if resolved:
            adam["weight_decay"] = 0.0
        if adam:
            o["adam"] = adam
    for key in ("spectral", "pose_graph", "consistency", "reweight"):
        if key in c:
            s = switch(c[key], key)
            if s is None:
                del c[key]
            else:
                c[key] = s
    if "geometric" in c:
        g = switch(c["geometric"], "geometric")
        frozen = c.get("pose_optim", {}).get("optimize", True) is False
        if g is None or (resolved and frozen):
            del c["geometric"]
        else:
            moved = {"points_per_frame": "points_per_frame", "edge_offsets": "edge_offsets",
                     "tau_scale": "tau_scale", "lr_rot": "lr_rotation",
                     "lr_trans": "lr_translation", "residual": "residual", "seed": "seed",
                     "threads": "threads"}
            opt = {}
            for old, new in moved.items():
                if old in g:
                    opt[new] = g.pop(old)
            if resolved:
                if opt.get("tau_scale", 0.0) < 0.0:
                    raise SystemExit("geometric.tau_scale < 0 (by sensor): not in shape 2")
                opt.setdefault("residual", "point_to_point")
                opt.setdefault("seed", 1)
                opt.setdefault("threads", 2)
                opt["min_distance"] = 0.15
                opt["normals"] = {"radius_m": 1.0, "min_neighbours": 6, "max_flatness": 0.3}
            if opt:
                g["optimizer"] = opt
            c["geometric"] = g
    l4 = c.get("lidar4d")
    if isinstance(l4, dict):
        for key in ("flow", "refine"):
            if key in l4:
                s = switch(l4[key], "lidar4d." + key)
                if s is None:
                    del l4[key]
                else:
                    l4[key] = s
    return c


def runs_of(results):
    for row in results.get("rows", []):
        for s in row.get("sequences", []):
            for run in s.get("runs", [s]):
                yield row, s, run


def migrate_file(path):
    with open(path, encoding="utf-8") as f:
        r = json.load(f)
    n = 0
    for row, s, run in runs_of(r):
        cfg = run.get("config")
        if not isinstance(cfg, dict):
            continue
        where = f"{path}: {row.get('method')} / {s.get('sequence')} seed {run.get('seed')}"
        if "grid" in cfg.get("field", {}):
            raise SystemExit(f"{where}: already in shape 2")
        if old_hash(cfg) != run.get("config_hash"):
            raise SystemExit(f"{where}: the recorded config does not hash to its config_hash "
                             f"{run.get('config_hash')} ({old_hash(cfg)}); refusing")
        run["config"] = reshape(cfg)
        n += 1
    with open(path, "w", encoding="utf-8") as f:
        f.write(json.dumps(r, indent=2, sort_keys=True, ensure_ascii=False) + "\n")
    print(f"{path}: {n} run configs reshaped")


if __name__ == "__main__":
    for p in sys.argv[1:] or sorted(glob.glob("results/tables/*/*/results.json")):
        migrate_file(p)
