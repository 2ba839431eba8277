// `sgnlf train --method M (sgnlf train --help lists them) [--pose-init gt|noisy|identity|odometry] --preset <name> --data <dataset> --out <run dir> [--seed N]
// [--config overrides.json] [--device SPEC] [--device-profile cpu|gpu|auto|FILE] [--no-resume] [--stop-at STEP] [--sequence S]
// [--start ID] [--frames N] [--test-frames P,...] [--sensor NAME|FILE] [--frequency standard|low|HZ]`:
// trains a run folder (resumes an interrupted
// one by default) and writes run.json (with the dataset options, which eval and render reuse),
// checkpoints and summary.json (and sensor.json when the sensor was estimated from plain scans).
#include <iostream>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "apps/sensor_rate_options.hpp"
#include "core/config.hpp"
#include "harness/context.hpp"
#include "pipeline/methods/registry.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::app {
namespace {

// "lidar-nerf, geonlf, ...": the registry's methods that train (the others are table rows).
std::string trainable_methods() {
  std::string s;
  for (const auto& m : pipeline::method_registry())
    if (m.implemented) s += (s.empty() ? "" : ", ") + m.name;
  return s;
}

struct TrainArgs {
  std::string method = "lidar-nerf", preset = "quick", data, out, config, device, pose_init;
  std::string device_profile;
  uint64_t seed = 1;
  bool no_resume = false;
  long stop_at = -1;
  LoadOptions load;
  SensorRateOptions sensor_rate;
};

const Registrar reg("train", "Train a method on a dataset into a run folder", [](CLI::App& sub) {
  auto a = std::make_shared<TrainArgs>();
  sub.add_option("--method", a->method, "Method: " + trainable_methods());
  sub.add_option("--pose-init", a->pose_init,
                 "Pose-free methods: initial poses gt, noisy (protocol §3, the presets' default), "
                 "identity or odometry (the built-in LiDAR odometry on the scans; config key "
                 "poses.init; recorded in run.json)");
  sub.add_option("--preset", a->preset, "Preset: paper, quick, smoke");
  sub.add_option("--data", a->data, "Dataset folder (synthetic or real layout)")->required();
  sub.add_option("--out", a->out, "Run folder")->required();
  sub.add_option("--seed", a->seed, "Seed");
  sub.add_option("--config", a->config, "JSON file of config keys overriding the preset");
  sub.add_option("--device", a->device, "OpenCL device index or name substring");
  add_device_profile_option(sub, a->device_profile);
  sub.add_flag("--no-resume", a->no_resume, "Start from scratch even if a checkpoint exists");
  sub.add_option("--stop-at", a->stop_at, "Stop after this step (checkpointed; resumable)");
  sub.add_option("--sequence", a->load.sequence, "Sequence / drive / scene of a real layout");
  sub.add_option("--start", a->load.start, "First frame id of the window");
  sub.add_option("--frames", a->load.frames, "Frames in the window (default: the protocol's 64 / 36)");
  sub.add_option("--test-frames", a->load.test_frames,
                 "Test views as positions in the window, comma-separated (default: the protocol's split)")
      ->delimiter(',');
  a->sensor_rate.add(sub);
  return std::function<int()>([a] {
    a->sensor_rate.apply(a->load);
    a->load.validate();
    pipeline::TrainRequest req;
    req.manifest.method = a->method;
    req.manifest.preset = a->preset;
    req.manifest.dataset = a->data;
    req.manifest.device = a->device;
    req.manifest.seed = a->seed;
    req.manifest.data_options = a->load;
    Json overrides = a->config.empty() ? Json::object() : load_config_file(a->config);
    std::string overrides_name = a->config.empty() ? "" : "--config " + a->config;
    if (!a->pose_init.empty()) {
      if (!pipeline::find_method(a->method).sections.pose_free)
        throw ConfigError("--pose-init: method '" + a->method + "' uses ground-truth poses");
      overrides = pipeline::merge_config_json(overrides, Json{{"poses", {{"init", a->pose_init}}}});
      overrides_name += (overrides_name.empty() ? "" : " + ") + std::string("--pose-init");
    }
    req.manifest.config = pipeline::resolve_config(
        a->method, a->preset, overrides, overrides_name.empty() ? "overrides" : overrides_name);
    req.run_dir = a->out;
    req.resume = !a->no_resume;
    req.stop_at = a->stop_at;
    cl::Runtime rt(a->device, a->device_profile);
    req.context = harness::context_block(&rt.device(), &rt.device_profile());
    const Json s = pipeline::train_run(rt, req);
    std::cout << s.dump(2) << "\n";
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
