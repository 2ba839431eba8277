// run_method() (method.hpp): the harness's entry point. "lidar-nerf" trains and evaluates a run
// folder through session.hpp; the other rows report implemented = false for now.
#include "pipeline/method.hpp"

#include <algorithm>
#include <chrono>

#include "pipeline/presets.hpp"
#include "pipeline/session.hpp"

namespace sgnlf::pipeline {

std::vector<std::string> known_methods() { return {"lidar-nerf", "lidar4d", "geonlf", "sg-nlf"}; }

bool method_implemented(const std::string& method) { return method == "lidar-nerf"; }

MethodResult run_method(const MethodRequest& req) {
  MethodResult res;
  if (!method_implemented(req.method)) {
    res.implemented = false;
    return res;
  }
  RunManifest m;
  m.method = req.method;
  m.preset = req.scale;
  m.dataset = req.dataset_dir;
  m.device = req.device;
  m.seed = req.seed;
  m.config = resolve_config(req.method, req.scale, req.overrides);
  cl::Runtime rt(req.device);
  TrainRequest tr;
  tr.manifest = m;
  tr.run_dir = req.out_dir;
  tr.show_progress = true;
  const Json summary = train_run(rt, tr);
  const auto t0 = std::chrono::steady_clock::now();
  LoadedRun run = load_run(rt, req.out_dir);
  const Json ev = eval_run(run, req.out_dir);
  const double eval_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.config = train_config_to_json(m.config);
  res.per_frame = ev.at("per_frame");
  res.metrics = ev.at("metrics");
  res.pose_metrics = nullptr;
  res.timings = Json{{"load", summary.at("load_seconds")},
                     {"train", summary.at("train_seconds")},
                     {"eval", eval_s}};
  res.extra = Json{{"seed", req.seed},
                   {"iterations", summary.at("end_step")},
                   {"samples_per_s", summary.at("samples_per_s")},
                   {"naive_baseline", ev.at("naive_baseline").at("metrics")}};
  return res;
}

}  // namespace sgnlf::pipeline
