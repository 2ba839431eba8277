// Contract between the table harness (runtime/harness) and the training pipeline: run one
// method (row) on one dataset (sequence) at one scale and return its metrics. The harness
// never trains by itself; the pipeline never writes tables.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config.hpp"

namespace sgnlf::pipeline {

struct MethodRequest {
  std::string method;       // "lidar-nerf", "lidar4d", "geonlf", "sg-nlf", or an ablation name
  std::string scale;        // "smoke", "quick", "paper"
  std::string dataset_dir;  // a dataset on disk (synthetic or real layout)
  std::string out_dir;      // run folder (checkpoints, renders, resolved config)
  uint64_t seed = 1;
  std::string device;       // OpenCL device spec ("" = default)
  std::string device_profile;  // cl/device_profile.hpp spec ("" = default)
  Json overrides = Json::object();  // config keys overriding the preset
  Json context = nullptr;  // where it runs (harness::context_block), into summary.json; or null
};

struct MethodResult {
  bool implemented = true;  // false: the method does not exist yet ("not implemented" row)
  Json config;              // resolved config
  Json per_frame;           // array: {frame, metrics...} for each test frame
  Json metrics;             // mean over test frames (protocol §4 names: cd, fscore, depth_rmse, ...)
  Json pose_metrics;        // ate_m, rpe_t_cm, rpe_r_deg (pose-free methods), or null
  Json timings;             // phase -> seconds
  Json extra;               // method-specific extras (seeds, iterations, ...)
};

// Methods known to the pipeline, and whether each is implemented in this build.
std::vector<std::string> known_methods();
bool method_implemented(const std::string& method);

// Trains and evaluates; throws on error. Returns implemented=false for unimplemented methods.
MethodResult run_method(const MethodRequest& request);

}  // namespace sgnlf::pipeline
