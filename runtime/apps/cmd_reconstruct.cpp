// `sgnlf reconstruct --scans DIR --out RUN [--method sg-nlf] [--preset quick] [--seed N]
// [--config overrides.json] [--device SPEC] [--sensor NAME|FILE] [--frequency standard|low|HZ]
// [--start ID] [--frames N] [--stride K] [--reference-poses FILE] [--verbose]`: from a folder of
// scans to poses, a field, its evaluation, renders, the scene's cloud and a report
// (workflow/reconstruct.hpp), one progress line with an ETA over the whole job, resumable by
// running the same command again. Prints a summary and the files; ATE/RPE only against
// reference poses.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>

#include "apps/command.hpp"
#include "apps/device_profile_option.hpp"
#include "apps/sensor_rate_options.hpp"
#include "core/config.hpp"
#include "core/log.hpp"
#include "workflow/reconstruct.hpp"

namespace sgnlf::app {
namespace {

struct ReconstructArgs {
  workflow::ReconstructRequest req;
  SensorRateOptions sensor_rate;
  bool verbose = false;
  std::string device_profile;
  bool json = false;
};

void print_metric_row(const char* name, const Json& m, const Json& n, const char* key) {
  if (!m.contains(key) || !m.at(key).is_number()) return;
  std::printf("  %-22s %10.4f %10.4f\n", name, m.at(key).get<double>(),
              n.contains(key) && n.at(key).is_number() ? n.at(key).get<double>() : 0.0);
}

void print_summary(const Json& j) {
  const Json& st = j.at("stages");
  const Json& odo = st.at("odometry");
  const Json& tr = st.at("train");
  const Json& ev = st.at("evaluate");
  std::printf("reconstructed %s: %ld scans, %ld held out\n", j.at("request").at("scans").get<std::string>().c_str(),
              odo.at("scans").get<long>(), ev.at("test_frames").get<long>());
  std::printf("  odometry %.1f s (%.1f scans/s), training %ld steps in %.0f s on %s\n",
              odo.at("seconds").get<double>(), odo.at("scans_per_second").get<double>(),
              tr.at("end_step").get<long>(), tr.value("train_seconds", 0.0),
              tr.value("device", std::string("?")).c_str());
  if (j.contains("pose_errors")) {
    const Json& p = j.at("pose_errors");
    std::printf("poses against the reference (SE(3)-aligned):\n  %-10s %9s %9s %9s %9s\n", "",
                "ATE m", "ATE h m", "RPE cm", "RPE deg");
    for (const char* k : {"odometry", "optimised"})  // ate_h_m: nan in records made before it
      std::printf("  %-10s %9.4f %9.4f %9.2f %9.3f\n", k, p.at(k).at("ate_m").get<double>(),
                  p.at(k).value("ate_h_m", std::nan("")), p.at(k).at("rpe_t_cm").get<double>(),
                  p.at(k).at("rpe_r_deg").get<double>());
    if (p.at("optimised").value("ate_reference", "") == "horizontal")
      std::printf("  the reference poses are planar (every z equal): judge by ATE h, the "
                  "horizontal ATE\n");
  } else {
    std::printf("poses: no reference poses, so no ATE (give --reference-poses FILE to score them)\n");
  }
  std::printf("held-out scans against the rendered views:\n  %-22s %10s %10s\n", "", "field", "naive");
  const Json& m = ev.at("metrics");
  const Json& n = ev.at("naive_baseline");
  print_metric_row("Chamfer distance (m^2)", m, n, "cd");
  print_metric_row("F-score", m, n, "fscore");
  print_metric_row("depth RMSE (m)", m, n, "depth_rmse");
  print_metric_row("depth PSNR (dB)", m, n, "depth_psnr");
  print_metric_row("intensity PSNR (dB)", m, n, "intensity_psnr");
  if (ev.contains("trajectory_check") && !ev.at("trajectory_check").value("converged", true))
    std::printf("WARNING: the poses did not converge: %s\n",
                ev.at("trajectory_check").value("reason", std::string()).c_str());
  std::printf("files:\n  %s\n  %s\n  %s\n  %s\n", odo.at("kitti").get<std::string>().c_str(),
              st.at("cloud").at("ply").get<std::string>().c_str(),
              st.at("cloud").at("pcd").get<std::string>().c_str(),
              st.at("report").at("file").get<std::string>().c_str());
}

const Registrar reg("reconstruct",
                    "From a folder of scans to poses, a field, renders, the scene's cloud and a report",
                    [](CLI::App& sub) {
  auto a = std::make_shared<ReconstructArgs>();
  auto& r = a->req;
  sub.add_option("--scans", r.scans, "Folder of scans (.bin, .pcd.bin, .pcd, .ply; or a dataset layout)")
      ->required();
  sub.add_option("--out", r.run_dir, "Job folder (a run folder: eval, render and report work on it)")
      ->required();
  sub.add_option("--method", r.method, "Pose-free method (sg-nlf, geonlf)")->capture_default_str();
  sub.add_option("--preset", r.preset, "Preset: quick, paper, smoke")->capture_default_str();
  sub.add_option("--seed", r.seed, "Seed")->capture_default_str();
  sub.add_option("--config", r.config, "JSON file of config keys overriding the preset");
  sub.add_option("--device", r.device, "OpenCL device index or name substring");
  add_device_profile_option(sub, a->device_profile);
  sub.add_option("--start", r.load.start, "First scan (index in name order)");
  sub.add_option("--frames", r.load.frames, "Scans to use (default: all of a plain folder)");
  sub.add_option("--stride", r.load.stride, "Take every k-th scan");
  sub.add_option("--reference-poses", r.reference_poses,
                 "KITTI poses file (line k: scan k in name order) to score the poses against");
  sub.add_flag("--verbose", a->verbose, "Show the stages' log lines (default: warnings only)");
  sub.add_flag("--json", a->json, "Print reconstruct.json instead of the summary");
  a->sensor_rate.add(sub);
  return std::function<int()>([a] {
    a->sensor_rate.apply(a->req.load);
    a->req.load.validate();
    // One progress line: the stages' info lines only on request (or SGNLF_LOG).
    if (!a->verbose && std::getenv("SGNLF_LOG") == nullptr && log::level() < log::Level::warn)
      log::set_level(log::Level::warn);
    cl::Runtime rt(a->req.device, a->device_profile);
    const Json j = workflow::reconstruct(rt, a->req);
    if (a->json)
      std::cout << j.dump(2) << "\n";
    else
      print_summary(j);
    return 0;
  });
});

}  // namespace
}  // namespace sgnlf::app
