// `sgnlf render --run <run dir> [--out <dir>] [--data <dataset>] [--device SPEC] [--poses FILE |
// --frames IDS] [--renderer fast|protocol] [--fast-config FILE]`: renders the test frames (or the
// recorded frames IDS, training frames too) of a trained run
// (npy arrays and PNGs of the rendering above the ground truth), or novel views at the poses of
// a KITTI-format trajectory file (npy, PNG and PCD per pose), and prints rays/s and frames/s.
// With `--baked SCENE` (from `sgnlf bake`), the views are ray-cast from the baked scene instead
// of rendered from the field (docs/baking.md).
#include <chrono>
#include <filesystem>
#include <iostream>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "apps/render_sampling_options.hpp"
#include "apps/fast_render_options.hpp"
#include "core/config.hpp"
#include "bake/baked_scene.hpp"
#include "io/trajectory_io.hpp"
#include "pipeline/run/session.hpp"

namespace sgnlf::app {
namespace {

struct RenderArgs {
  std::string run, out, data, device, poses, sensor, device_profile, baked, baked_head = "field";
  float baked_head_spread = -1.0f;
  std::vector<int> frames;
  FastRenderOptions fast;
  pipeline::RenderSampling sampling;
};

const Registrar reg("render", "Render the test frames of a trained run, or novel views", [](CLI::App& sub) {
  auto a = std::make_shared<RenderArgs>();
  sub.add_option("--run", a->run, "Run folder")->required();
  sub.add_option("--out", a->out, "Output folder (default <run>/renders)");
  sub.add_option("--data", a->data, "Dataset folder (default: the one the run trained on)");
  sub.add_option("--device", a->device, "OpenCL device index or name substring");
  add_device_profile_option(sub, a->device_profile);
  auto* poses = sub.add_option("--poses", a->poses,
                 "Render these views instead of the test frames: KITTI trajectory file, one "
                 "T_world_lidar per line (12 numbers, the dataset's world frame, metres)");
  sub.add_option("--frames", a->frames,
                 "Render these recorded frames instead of the test frames (frame ids, comma "
                 "separated; training frames too), each with its ground truth")
      ->delimiter(',')
      ->excludes(poses);
  sub.add_option("--sensor", a->sensor,
                 "Render for this sensor instead of the recording one: a preset (kitti360 = "
                 "HDL-64E, nuscenes = HDL-32E) or a sensor JSON file (keys of sensor.json); "
                 "without --poses, at the test frames' poses");
  a->fast.add(sub, "fast", "");
  sub.add_option("--baked", a->baked,
                 "Ray-cast this baked scene (`sgnlf bake RUN --out SCENE`) instead of rendering "
                 "the field: same poses, sensors and outputs (docs/baking.md)");
  sub.add_option("--baked-head", a->baked_head,
                 "With --baked: field (the run's LiDAR head with the ray's own direction, at the "
                 "baked surface or at the weight's quartiles where it spreads over more than a "
                 "voxel; default) or vertex (the scene's baked per-vertex "
                 "return probability and intensity: no field at all)")
      ->check(CLI::IsMember({"field", "vertex"}));
  sub.add_option("--baked-head-spread", a->baked_head_spread,
                 "With the field head: metres between the weight's 1/8 and 7/8 quartiles beyond "
                 "which a ray takes the head at each quartile instead of once (default: the "
                 "scene's voxel; larger is faster, docs/baking.md)");
  add_render_sampling_options(sub, a->sampling);
  return std::function<int()>([a] {
    // Poses and settings first: bad input fails before the run is loaded.
    if (!a->frames.empty() && !a->sensor.empty())
      throw ConfigError("render: --frames renders with the recording sensor; drop --sensor");
    const std::vector<Pose> poses =
        a->poses.empty() ? std::vector<Pose>{} : io::read_kitti_poses(a->poses);
    const render::FastRenderConfig fcfg = a->fast.config();
    std::unique_ptr<Sensor> sensor;
    if (!a->sensor.empty())
      sensor = std::make_unique<Sensor>(
          a->sensor == "kitti360" || a->sensor == "nuscenes"
              ? sensor_preset(a->sensor)
              : sensor_from_json(load_config_file(a->sensor), a->sensor));
    cl::Runtime rt(a->device, a->device_profile);
    const std::unique_ptr<bake::BakedScene> baked_scene =
        a->baked.empty() ? nullptr : std::make_unique<bake::BakedScene>(bake::read_baked_scene(a->baked));
    auto run = pipeline::load_run(rt, a->run, a->data, a->sampling);
    const std::string out =
        a->out.empty() ? (std::filesystem::path(a->run) / "renders").string() : a->out;
    const auto fast = baked_scene ? nullptr : a->fast.make(rt, run, fcfg);
    const auto baked = baked_scene ? std::make_unique<pipeline::BakedRenderer>(
                                         rt, *baked_scene, run.model->render_config(),
                                         a->baked_head == "field" ? run.model.get() : nullptr,
                                         a->baked_head_spread)
                                   : nullptr;
    const std::string renderer = baked ? std::string("baked, ") + baked->head() + " head" : a->fast.renderer;
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Pose> views = poses;
    if (views.empty() && sensor)
      for (int f : run.dataset->split.test) views.push_back(run.T_world_lidar[size_t(f)]);
    const Json files = views.empty()
                           ? pipeline::render_run(run, out, fast.get(), a->frames, baked.get())
                           : pipeline::render_poses(run, views, out, fast.get(), sensor.get(), baked.get());
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const long frames = long(files.size());
    const Sensor& shown = sensor ? *sensor : run.scene->sensor;
    const long rays = frames * long(shown.height) * long(shown.width);
    // Render time without writing files and (fast) without the grid builds.
    const double render_s = fast    ? fast->counts().render_seconds
                            : baked ? baked->counts().render_seconds
                                    : total_s;
    Json summary{{"renderer", renderer}, {"frames", frames}, {"rays", rays},
                 {"render_s", render_s}, {"wall_s", total_s},
                 {"rays_per_s", render_s > 0 ? double(rays) / render_s : 0.0},
                 {"frames_per_s", render_s > 0 ? double(frames) / render_s : 0.0}};
    if (fast) {
      const auto& c = fast->counts();
      summary["grid_s"] = c.grid_seconds;
      summary["grids"] = c.grids;
      summary["density_rows_per_ray"] = rays > 0 ? double(c.evaluated) / double(rays) : 0.0;
      summary["head_rows_per_ray"] = rays > 0 ? double(c.head_rows) / double(rays) : 0.0;
      if (fcfg.layout == "march" && rays > 0)
        summary["density_rows_per_ray_by_kind"] =
            Json{{"coarse", double(c.march.coarse) / double(rays)},
                 {"fine", double(c.march.fine) / double(rays)},
                 {"outside_grid", double(c.march.outside) / double(rays)},
                 {"dropped_after_hit", double(c.march.dropped) / double(rays)}};
      summary["fast_config"] = fcfg.to_json();
    }
    if (baked && rays > 0) {
      const auto& c = baked->counts();
      summary["head_rows_per_ray"] = double(c.head_rows) / double(rays);
      summary["spread_ray_fraction"] = double(c.spread_rays) / double(rays);
    }
    std::cerr << "render: " << frames << " frame(s) of " << shown.height << " x "
              << shown.width << " in " << render_s << " s ("
              << summary["rays_per_s"].get<double>() << " rays/s, "
              << summary["frames_per_s"].get<double>() << " frames/s, " << renderer
              << " renderer)\n";
    std::cout << Json{{"files", files}, {"speed", summary}}.dump(2) << "\n";
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
