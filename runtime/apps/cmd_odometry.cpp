// `sgnlf odometry --data <dataset> --out poses.txt [--tum poses.tum.txt] [--svg top.svg]
// [--log odometry.json] [--config odometry.json] [--threads N] [--deskew] [--sequence S] [--start ID]
// [--frames N] [--frequency standard|low|HZ] [--sensor NAME|FILE] [--stride K]`: the LiDAR odometry alone
// (odometry/lidar_odometry.hpp) on a dataset's scans. Writes T_world_lidar (first frame at the
// identity) as KITTI (--out) and TUM (--tum, default <out without .txt>.tum.txt) files, prints
// progress with scans/s, and ATE/RPE (protocol §4) when the dataset has ground-truth poses.
// Exit status 1 when any frame failed to register (the files are still written).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "apps/sensor_rate_options.hpp"
#include "core/config.hpp"
#include "core/progress.hpp"
#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"
#include "io/trajectory_io.hpp"
#include "io/trajectory_svg.hpp"
#include "metrics/pose_errors.hpp"
#include "odometry/trajectory.hpp"

namespace sgnlf::app {
namespace {

struct OdometryArgs {
  std::string data, out, tum, svg, log, config;
  int threads = 0;
  bool deskew = false;
  LoadOptions load;
  SensorRateOptions sensor_rate;
};

std::string default_tum_path(const std::string& kitti) {
  std::filesystem::path p(kitti);
  if (p.extension() == ".txt") p.replace_extension();
  return p.string() + ".tum.txt";
}

const Registrar reg("odometry", "Estimate poses from raw scans with the built-in LiDAR odometry", [](CLI::App& sub) {
  auto a = std::make_shared<OdometryArgs>();
  sub.add_option("--data", a->data, "Dataset folder (synthetic, KITTI, KITTI-360, nuScenes, or a folder of scans)")->required();
  sub.add_option("--out", a->out, "KITTI trajectory file to write (T_world_lidar, first frame = identity)")->required();
  sub.add_option("--tum", a->tum, "TUM trajectory file (default: <out without .txt>.tum.txt)");
  sub.add_option("--svg", a->svg, "Top view of the trajectory (and of the ground truth when known)");
  sub.add_option("--log", a->log, "JSON file: config, per-frame registration results, metrics");
  sub.add_option("--config", a->config, "JSON file of odometry options (odometry/odometry_config.hpp)");
  sub.add_option("--threads", a->threads, "Threads of the registration (overrides the config)");
  sub.add_flag("--deskew", a->deskew, "Deskew each scan with the sensor's time model (config 'deskew': true)");
  sub.add_option("--sequence", a->load.sequence, "Sequence / drive / scene of a real layout");
  sub.add_option("--start", a->load.start, "First frame id of the window");
  sub.add_option("--frames", a->load.frames, "Frames in the window (default: the protocol's 64 / 36)");
  sub.add_option("--stride", a->load.stride, "Take every k-th frame of the native stream");
  a->sensor_rate.add(sub);
  return std::function<int()>([a] {
    a->sensor_rate.apply(a->load);
    a->load.validate();
    odometry::OdometryConfig cfg;
    if (!a->config.empty()) {
      const Json j = load_config_file(a->config);
      ConfigReader r(j, a->config);
      cfg = odometry::OdometryConfig::from_json(r);
    }
    if (a->threads > 0) cfg.threads = a->threads;
    if (a->deskew) cfg.deskew = true;
    cfg.validate("odometry");
    const Dataset d = load_dataset(a->data, a->load);
    std::vector<const std::vector<PointXYZI>*> scans;
    std::vector<double> stamps;
    for (const auto& f : d.frames) {
      scans.push_back(&f.points);
      stamps.push_back(f.timestamp_s);
    }
    Progress progress("odometry " + d.name, long(scans.size()), 2.0);
    const auto res = odometry::estimate_trajectory(
        scans, stamps, cfg, d.sensor, [&](size_t k, const odometry::FrameResult& fr) {
          char extra[160];
          const double rate = double(k + 1) / std::max(progress.elapsed_s(), 1e-9);
          std::snprintf(extra, sizeof extra, "%.1f scans/s  fitness %.2f  sigma %.2f m%s", rate,
                        fr.registration.fitness, fr.sigma, fr.ok() ? "" : "  FAILED");
          progress.update(long(k + 1), extra);
        });
    char done[96];
    std::snprintf(done, sizeof done, "%.1f scans/s", res.scans_per_second());
    progress.finish(done);
    for (int k : res.failed)
      std::fprintf(stderr, "sgnlf odometry: frame %d (id %d) did not register: %s\n", k,
                   d.frames[size_t(k)].id, res.frames[size_t(k)].registration.failure.c_str());

    const std::string tum = a->tum.empty() ? default_tum_path(a->out) : a->tum;
    const auto parent = std::filesystem::path(a->out).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    io::write_kitti_poses(a->out, res.T_world_lidar);
    io::write_tum_poses(tum, stamps, res.T_world_lidar);
    std::printf("%zu scans in %.2f s (%.1f scans/s), %zu failed; wrote %s and %s\n",
                res.frames.size(), res.seconds, res.scans_per_second(), res.failed.size(),
                a->out.c_str(), tum.c_str());

    const bool has_gt = d.has_reference_poses;
    Json metrics = nullptr;
    std::vector<Pose> gt_aligned;
    if (has_gt && d.frames.size() >= 2) {
      const std::vector<Pose> gt = gt_poses(d);
      const auto e = metrics::compute_pose_errors(res.T_world_lidar, gt);
      std::printf("ATE %.3f m (horizontal %.3f m)  RPE %.2f cm %.3f deg  (%zu frames, SE(3) "
                  "Umeyama, protocol §4)\n",
                  e.ate_m, e.ate_h_m, e.rpe_t_cm, e.rpe_r_deg, gt.size());
      const bool planar = d.planar_reference || e.planar_reference;
      if (planar)
        std::printf("the reference poses are planar (nuScenes' ego poses, z = 0): judge by the horizontal ATE\n");
      metrics = Json{{"ate_m", e.ate_m}, {"ate_h_m", e.ate_h_m},
                     {"ate_reference", planar ? "horizontal" : "3d"},
                     {"rpe_t_cm", e.rpe_t_cm}, {"rpe_r_deg", e.rpe_r_deg}};
      // Ground truth expressed in the odometry's frame (first pose at the identity) for the picture.
      const Pose T0_inv = gt.front().inverse();
      for (const Pose& T : gt) gt_aligned.push_back(T0_inv * T);
    }
    if (!a->svg.empty()) {
      std::vector<io::SvgTrajectory> trajs;
      std::vector<std::pair<int, int>> links;
      if (!gt_aligned.empty()) {
        trajs.push_back({"ground truth (first pose at the identity)", "#2ca02c", gt_aligned});
        links.push_back({0, 1});
      }
      trajs.push_back({"odometry", "#d62728", res.T_world_lidar});
      io::write_trajectory_svg(a->svg, "sgnlf odometry: " + d.name, trajs, links);
    }
    if (!a->log.empty()) {
      Json frames = Json::array();
      for (size_t k = 0; k < res.frames.size(); ++k) {
        const auto& fr = res.frames[k];
        frames.push_back(Json{{"frame", d.frames[k].id},
                              {"ok", fr.ok()},
                              {"initialised_map", fr.initialised_map},
                              {"converged", fr.registration.converged},
                              {"iterations", fr.registration.iterations},
                              {"fitness", fr.registration.fitness},
                              {"rmse_m", fr.registration.rmse},
                              {"sigma_m", fr.sigma},
                              {"source_points", fr.source_points},
                              {"map_points", fr.map_points},
                              {"failure", fr.registration.failure}});
      }
      write_json_file(a->log, Json{{"dataset", d.name}, {"source", d.source}, {"config", cfg.to_json()},
                                   {"seconds", res.seconds}, {"scans_per_second", res.scans_per_second()},
                                   {"failed", res.failed}, {"metrics", metrics}, {"frames", frames}});
    }
    return res.failed.empty() ? 0 : 1;
  });
});

}  // namespace
}  // namespace sgnlf::app
