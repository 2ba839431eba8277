// `sgnlf eval --run <run dir> [--json] [--data <dataset>] [--device SPEC] [--samples N]
// [--importance M] [--depth expected|median] [--sensor NAME|FILE] [--frequency standard|low|HZ]`: protocol §4 metrics of a trained run's test frames and of the naive
// baseline; writes <run>/metrics.json.
#include <cmath>
#include <cstdio>
#include <iostream>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "apps/render_sampling_options.hpp"
#include "apps/fast_render_options.hpp"
#include "apps/sensor_rate_options.hpp"
#include "bake/baked_scene.hpp"
#include "core/config.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::app {
namespace {

struct EvalArgs {
  std::string run, data, device, device_profile, baked, baked_head = "field";
  float baked_head_spread = -1.0f;
  pipeline::RenderSampling sampling;
  FastRenderOptions fast;
  SensorRateOptions sensor_rate;
  bool json = false;
};

std::string num(const Json& v) {
  if (!v.is_number()) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", v.get<double>());
  return buf;
}

const Registrar reg("eval", "Evaluate a trained run (and the naive baseline)", [](CLI::App& sub) {
  auto a = std::make_shared<EvalArgs>();
  sub.add_option("--run", a->run, "Run folder")->required();
  sub.add_option("--data", a->data, "Dataset folder (default: the one the run trained on)");
  sub.add_option("--device", a->device, "OpenCL device index or name substring");
  add_device_profile_option(sub, a->device_profile);
  add_render_sampling_options(sub, a->sampling);
  sub.add_flag("--json", a->json, "Print the metrics JSON");
  a->sensor_rate.add(sub);
  sub.get_option("--sensor")->description(
      "Load the data with this sensor instead of the run's (run.json's dataset_options, else the "
      "sensor.json train wrote for an estimated sensor): " + sub.get_option("--sensor")->get_description());
  sub.get_option("--frequency")->description(
      "Instead of the run's; must select the frames the run trained on: " +
      sub.get_option("--frequency")->get_description());
  a->fast.add(sub, "protocol",
              " (the tables'); fast writes <run>/metrics-fast.json, to compare with metrics.json");
  sub.add_option("--baked", a->baked,
                 "Score the views ray-cast from this baked scene (`sgnlf bake`) instead; writes "
                 "<run>/metrics-baked.json (docs/baking.md)");
  sub.add_option("--baked-head", a->baked_head,
                 "With --baked: field (the run's head at the baked surface, or at the weight's "
                 "quartiles where it spreads over more than a voxel; default) "
                 "or vertex (the scene's per-vertex attributes)")
      ->check(CLI::IsMember({"field", "vertex"}));
  sub.add_option("--baked-head-spread", a->baked_head_spread,
                 "With the field head: metres between the weight's 1/8 and 7/8 quartiles beyond "
                 "which a ray takes the head at each quartile instead of once (default: the "
                 "scene's voxel; larger is faster, docs/baking.md)");
  return std::function<int()>([a] {
    const render::FastRenderConfig fcfg = a->fast.config();
    const std::unique_ptr<bake::BakedScene> baked_scene =
        a->baked.empty() ? nullptr : std::make_unique<bake::BakedScene>(bake::read_baked_scene(a->baked));
    cl::Runtime rt(a->device, a->device_profile);
    LoadOptions data_options = pipeline::read_manifest(a->run).data_options;
    a->sensor_rate.apply(data_options);
    data_options.validate();
    auto run = pipeline::load_run(rt, a->run, a->data, a->sampling,
                                  a->sensor_rate.any() ? &data_options : nullptr);
    const auto fast = baked_scene ? nullptr : a->fast.make(rt, run, fcfg);
    const auto baked = baked_scene ? std::make_unique<pipeline::BakedRenderer>(
                                         rt, *baked_scene, run.model->render_config(),
                                         a->baked_head == "field" ? run.model.get() : nullptr,
                                         a->baked_head_spread)
                                   : nullptr;
    const Json j = pipeline::eval_run(run, a->run, fast.get(), nullptr, baked.get());
    if (a->json) {
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    const Json& m = j.at("metrics");
    const Json& n = j.at("naive_baseline").at("metrics");
    const Json& rs = j.at("render_sampling");
    std::printf("%s (%s) on %s, step %ld, %zu test frames, rendered with %d + %d samples, %s depth\n",
                j["method"].get<std::string>().c_str(), j["preset"].get<std::string>().c_str(),
                j["dataset"].get<std::string>().c_str(), j["step"].get<long>(),
                j["per_frame"].size(), rs.at("n_samples").get<int>(), rs.at("n_importance").get<int>(),
                rs.at("depth").get<std::string>().c_str());
    std::printf("%-18s %12s %12s\n", "metric", "model", "naive");
    for (auto it = m.begin(); it != m.end(); ++it)
      std::printf("%-18s %12s %12s\n", it.key().c_str(), num(it.value()).c_str(),
                  num(n.contains(it.key()) ? n.at(it.key()) : Json()).c_str());
    if (j.contains("renderer") && j.at("renderer").at("name") == "baked") {
      const Json& r = j.at("renderer");
      std::printf("\nbaked scene: %.2f s ray casting the test views (%.1f frames/s, %.3g rays/s), "
                  "%.1f MiB; %s head, %.2f rows per ray\n",
                  r.at("render_seconds").get<double>(), r.at("frames_per_s").get<double>(),
                  r.at("rays_per_s").get<double>(), r.at("scene_bytes").get<double>() / (1 << 20),
                  r.at("head").get<std::string>().c_str(), r.at("head_rows_per_ray").get<double>());
    } else if (j.contains("renderer")) {
      const Json& r = j.at("renderer");
      std::printf("\nfast renderer: %.1f s rendering (%.1f s occupancy grid), %.1f density and %.1f "
                  "head rows per ray (protocol: every sample)\n",
                  r.at("render_seconds").get<double>(), r.at("grid_seconds").get<double>(),
                  r.at("density_rows_per_ray").get<double>(), r.at("head_rows_per_ray").get<double>());
      if (r.contains("density_rows_per_ray_by_kind")) {
        const Json& k = r.at("density_rows_per_ray_by_kind");
        std::printf("density rows per ray by kind: %.1f coarse, %.1f fine, %.1f outside the grid, "
                    "%.1f dropped after a hit\n",
                    k.at("coarse").get<double>(), k.at("fine").get<double>(),
                    k.at("outside_grid").get<double>(), k.at("dropped_after_hit").get<double>());
      }
    } else {
      std::printf("\nprotocol renderer: %.1f s rendering the test views\n",
                  j.at("render_eval_seconds").get<double>());
    }
    if (j.contains("pose_metrics")) {
      const Json& p = j.at("pose_metrics");
      const Json& i = j.at("initial_pose_metrics");
      std::printf("\nposes over %ld frames (SE(3)-aligned, protocol §4), initial: %s\n",
                  p.at("frames").get<long>(), j.at("pose_init").get<std::string>().c_str());
      std::printf("%-18s %12s %12s\n", "pose", "optimised", "initial");
      for (const char* k : {"ate_m", "ate_h_m", "rpe_t_cm", "rpe_r_deg"})
        std::printf("%-18s %12s %12s\n", k, num(p.at(k)).c_str(), num(i.at(k)).c_str());
      if (p.value("ate_reference", "") == "horizontal")
        std::printf("the reference poses are planar (every z equal): judge by ate_h_m, the "
                    "horizontal ATE\n");
    }
    if (j.contains("trajectory_check") && !j.at("trajectory_check").at("converged").get<bool>())
      std::printf("\nWARNING: the poses did not converge: %s\n",
                  j.at("trajectory_check").at("reason").get<std::string>().c_str());
    if (j.contains("pose_graph")) {
      const Json& g = j.at("pose_graph");
      std::printf("\nconfidence-aware pose graph (epoch %ld): %ld non-adjacent edges in use (%s)\n",
                  g.at("epoch").get<long>(), g.at("non_adjacent_edges").get<long>(),
                  g.at("file").get<std::string>().c_str());
    }
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
