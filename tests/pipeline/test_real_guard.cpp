// Real-data guard: the geometric stage alone and the built-in odometry on the
// real nuScenes scene-0916 (first 36 keyframes at 2 Hz), each held to a bound that the code before
// the real-scan fix failed. The twins cannot catch a change that breaks real scans (they are
// boxy, static, and hold no returns of the vehicle itself); this scene can.
//
// Measured (docs/studies/real-scans/README.md):
// - the coarse alignment below with 2000 points a frame and 200 steps: 3.193 m → 0.160 m
//   (4000 points: 0.176 m); before the fix (the vehicle's own returns in the frame's points)
//   the same schedule stopped at 1.66 m and 1000 points end at 0.38 m;
// - the odometry: 0.182 m.
#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"
#include "metrics/pose_errors.hpp"
#include "pipeline/train/geometric_stage.hpp"
#include "pipeline/train/pose_check.hpp"
#include "pipeline/train/pose_init.hpp"
#include "posegraph/annealed_run.hpp"
#include "support/real_data.hpp"

using namespace sgnlf;

namespace {

const std::string kScene = "nuscenes-mini-scene-0916";
// The in-repo sample holds 2 of the scene's keyframes: these bounds are for the protocol's 36.
const std::string kNeeds = "the protocol's 36 keyframes of scene-0916; the in-repo sample holds 2";

Dataset load_scene(const std::string& dir) {
  LoadOptions o;
  o.sequence = "scene-0916";
  o.frames = 36;
  return load_dataset(dir, o);
}

}  // namespace

TEST_CASE("real scene-0916: the coarse alignment reaches 0.25 m ATE from the noisy start", "[real]") {
  const test::RealData r = test::full_real_data(kScene, kNeeds);
  if (!r) return;
  const std::string dir = r.path;
  const Dataset d = load_scene(dir);
  REQUIRE(d.frames.size() == 36);
  const std::vector<Pose> gt = gt_poses(d);
  pipeline::PoseInitConfig pi;
  pi.init = "noisy";
  std::vector<Pose> T = pipeline::initial_poses(d, pi);
  const double ate0 = metrics::compute_pose_errors(T, gt).ate_m;
  CHECK(ate0 == Approx(3.193).margin(0.01));  // the protocol's start (seed 1)

  // The GeoNLF quick preset's coarse alignment (geometric_stage: τ 1.5, lr 0.01 rad / 0.1 m
  // decaying to ×0.05, edges (i, i+1), (i, i+2), 200 steps in calls of 10), with 2000 points a
  // frame instead of 4000 to keep it to seconds.
  posegraph::GeometricConfig cfg;
  cfg.points_per_frame = 2000;
  cfg.threads = 2;
  cfg.lr_rotation = 1e-2;
  cfg.lr_translation = 1e-1;
  cfg.tau_scale = 1.5;
  cfg.steps = 10;
  std::vector<std::vector<PointXYZI>> scans;
  for (const auto& f : d.frames) scans.push_back(f.points);
  auto clouds = std::make_shared<const std::vector<posegraph::FrameCloud>>(cfg.clouds(scans));
  auto loss = std::make_shared<const posegraph::GraphLoss>(
      clouds, posegraph::sequential_edges(int(d.frames.size()), cfg.edge_offsets), cfg.min_distance,
      cfg.threads, cfg.direction());
  posegraph::AnnealConfig an;
  an.steps = 200;
  an.per_call = 10;
  an.lr_final = 0.05;
  posegraph::run_annealed(loss, cfg, an, T);
  const auto e = metrics::compute_pose_errors(T, gt);
  INFO("ATE " << e.ate_m << " m, RPE " << e.rpe_t_cm << " cm " << e.rpe_r_deg << " deg");
  CHECK(e.ate_m < 0.25);
  CHECK(e.rpe_t_cm < 10.0);
  // The convergence check (no ground truth) agrees: every neighbour overlaps.
  const auto check = pipeline::check_run_poses(d, T);
  INFO("median overlap " << check.median_overlap << ": " << check.reason);
  CHECK(check.converged);
  CHECK(check.median_overlap > 0.5);
  // ... and flags the start it came from.
  CHECK_FALSE(pipeline::check_run_poses(d, pipeline::initial_poses(d, pi)).converged);
}

TEST_CASE("real scene-0916: the odometry stays within 0.21 m ATE", "[real]") {
  const test::RealData r = test::full_real_data(kScene, kNeeds);
  if (!r) return;
  const std::string dir = r.path;
  const Dataset d = load_scene(dir);
  pipeline::PoseInitConfig pi;
  pi.init = "odometry";
  const std::vector<Pose> T = pipeline::initial_poses(d, pi);  // throws when a frame fails
  const auto e = metrics::compute_pose_errors(T, gt_poses(d));
  INFO("ATE " << e.ate_m << " m, RPE " << e.rpe_t_cm << " cm " << e.rpe_r_deg << " deg");
  CHECK(e.ate_m < 0.21);  // measured 0.182 m
  CHECK(e.rpe_t_cm < 10.0);
}
