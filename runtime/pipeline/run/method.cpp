// run_method() (method.hpp): the harness's entry point. Every implemented method of the
// registry (methods/registry.hpp) trains and evaluates a run folder through session.hpp; the
// others report implemented = false.
#include "pipeline/run/method.hpp"

#include <algorithm>
#include <chrono>

#include "core/config.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::pipeline {

std::vector<std::string> known_methods() {
  std::vector<std::string> names;
  for (const auto& m : method_registry()) names.push_back(m.name);
  return names;
}

bool method_implemented(const std::string& method) {
  for (const auto& m : method_registry())
    if (m.name == method) return m.implemented;
  return false;
}

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
  cl::Runtime rt(req.device, req.device_profile);
  TrainRequest tr;
  tr.manifest = m;
  tr.run_dir = req.out_dir;
  tr.show_progress = true;
  tr.context = req.context;
  const Json summary = train_run(rt, tr);
  const auto t0 = std::chrono::steady_clock::now();
  LoadedRun run = load_run(rt, req.out_dir);
  const Json ev = eval_run(run, req.out_dir);
  const double eval_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  res.config = train_config_to_json(m.config);
  res.per_frame = ev.at("per_frame");
  res.metrics = ev.at("metrics");
  res.pose_metrics = ev.contains("pose_metrics") ? ev.at("pose_metrics") : Json(nullptr);
  res.timings = Json{{"load", summary.at("load_seconds")},
                     {"train", summary.at("train_seconds")},
                     {"eval", eval_s}};
  res.extra = Json{{"seed", req.seed},
                   {"iterations", summary.at("end_step")},
                   {"samples_per_s", summary.at("samples_per_s")},
                   {"naive_baseline", ev.at("naive_baseline").at("metrics")}};
  if (summary.contains("geometric_seconds"))
    res.extra["geometric_seconds"] = summary.at("geometric_seconds");
  if (ev.contains("initial_pose_metrics")) {
    res.extra["initial_pose_metrics"] = ev.at("initial_pose_metrics");
    res.extra["pose_init"] = ev.at("pose_init");
  }
  return res;
}

}  // namespace sgnlf::pipeline
