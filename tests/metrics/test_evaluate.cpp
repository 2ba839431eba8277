// evaluate_view / mean_metrics JSON (protocol §4) and the naive nearest-scan baseline.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <set>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "metrics/chamfer.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/naive_baseline.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;

namespace {

Sensor small_sensor() {
  Sensor s = sensor_preset("kitti360");
  s.name = "small";
  s.height = 16;
  s.width = 64;
  return s;
}

// A ground-truth image with ~20 % dropped pixels, ranges in [2, 50] m, intensities in [0, 1].
RangeImage random_gt(const Sensor& s, uint64_t seed) {
  Rng rng(seed);
  RangeImage img(s.height, s.width);
  for (size_t i = 0; i < img.size(); ++i) {
    if (rng.uniform() < 0.2f) continue;
    img.range[i] = rng.uniform(2.f, 50.f);
    img.intensity[i] = rng.uniform();
    img.ray_drop[i] = 1.f;
  }
  return img;
}

}  // namespace

TEST_CASE("evaluate_view of a perfect prediction", "[metrics][evaluate]") {
  const Sensor s = small_sensor();
  const RangeImage gt = random_gt(s, 4);
  RangeImage pred = gt;
  for (size_t i = 0; i < pred.size(); ++i) pred.ray_drop[i] = gt.ray_drop[i] > 0 ? 0.9f : 0.1f;
  const Json j = evaluate_view(s, pred, gt);
  std::set<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.insert(k);
  CHECK(keys == std::set<std::string>(view_metric_keys().begin(), view_metric_keys().end()));
  CHECK(keys.size() == 22);
  CHECK(j["cd"].get<double>() == 0.0);
  CHECK(j["fscore"].get<double>() == 1.0);
  CHECK(j["cd_pred_to_gt"].get<double>() == 0.0);
  CHECK(j["cd_gt_to_pred"].get<double>() == 0.0);
  CHECK(j["depth_rmse"].get<double>() == 0.0);
  CHECK(j["depth_psnr"].is_null());  // MSE = 0
  CHECK(j["depth_ssim"].get<double>() == Approx(1.0));
  CHECK(j["depth_delta1"].get<double>() == 1.0);
  CHECK(j["depth_lpips"].is_null());
  CHECK(j["intensity_ssim"].get<double>() == Approx(1.0));
  CHECK(j["raydrop_acc"].get<double>() == 1.0);
  CHECK(j["raydrop_f1"].get<double>() == 1.0);
  CHECK(j["raydrop_rmse"].get<double>() == Approx(0.1).epsilon(1e-6));
  for (const char* k : {"depth_mse_returns", "depth_mse_missed", "depth_mse_false",
                        "raydrop_missed", "raydrop_false"})
    CHECK(j[k].get<double>() == 0.0);
}

TEST_CASE("evaluate_view masks the prediction by probability > 0.5", "[metrics][evaluate]") {
  const Sensor s = small_sensor();
  const RangeImage gt = random_gt(s, 5);
  RangeImage pred = gt;
  for (size_t i = 0; i < pred.size(); ++i) pred.ray_drop[i] = gt.ray_drop[i];
  size_t k = 0;
  while (gt.range[k] == 0.f) ++k;
  pred.ray_drop[k] = 0.4f;   // one true return predicted as dropped
  pred.intensity[k] = 0.3f;  // must not count either
  // Ground truth is masked by its label: a stray intensity or range without a return is ignored.
  RangeImage gt_stray = gt;
  size_t z = 0;
  while (gt.ray_drop[z] != 0.f) ++z;
  gt_stray.intensity[z] = 0.8f;
  gt_stray.range[z] = 7.f;
  const Json j = evaluate_view(s, pred, gt_stray);
  const double n = double(gt.size());
  // Depth: only pixel k differs, pred → 0 → clipped 1e-6.
  CHECK(j["depth_rmse"].get<double>() ==
        Approx((double(gt.range[k]) - 1e-6) / std::sqrt(n)).epsilon(1e-9));
  CHECK(j["intensity_rmse"].get<double>() ==
        Approx((std::max(double(gt.intensity[k]), 1e-6) - 1e-6) / std::sqrt(n)).epsilon(1e-9));
  CHECK(j["raydrop_acc"].get<double>() == Approx((n - 1) / n));
  // The one missed return is all of the depth error; the stray ground truth is no false return.
  const double ek = double(gt.range[k]) - 1e-6;
  CHECK(j["depth_mse_missed"].get<double>() == Approx(ek * ek / n).epsilon(1e-9));
  CHECK(j["depth_mse_returns"].get<double>() == 0.0);
  CHECK(j["depth_mse_false"].get<double>() == 0.0);
  CHECK(j["raydrop_missed"].get<double>() == Approx(1.0 / n));
  CHECK(j["raydrop_false"].get<double>() == 0.0);
  // CD: d1 all 0; d2 = 0 except GT point k, whose NN is its nearest other GT point.
  const auto gt_pts = unproject(s, gt);
  const Eigen::Vector3f pk = pixel_direction(s, int(k / s.width), int(k % s.width)) * gt.range[k];
  double nn = std::numeric_limits<double>::infinity();
  for (const auto& p : gt_pts) {
    const double d = (Eigen::Vector3f(p.x, p.y, p.z) - pk).squaredNorm();
    if (d > 0) nn = std::min(nn, d);
  }
  const double n_gt = double(gt_pts.size());
  CHECK(j["cd"].get<double>() == Approx(nn / n_gt).epsilon(1e-5));
  const double p2 = nn < 0.05 ? 1.0 : (n_gt - 1) / n_gt;
  CHECK(j["fscore"].get<double>() == Approx(2 * p2 / (1 + p2)).epsilon(1e-12));
}

TEST_CASE("evaluate_view rejects size mismatches and NaN", "[metrics][evaluate]") {
  const Sensor s = small_sensor();
  const RangeImage gt = random_gt(s, 6);
  RangeImage small(8, 64);
  try {
    evaluate_view(s, small, gt);
    FAIL("no throw");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find("8x64") != std::string::npos);
    CHECK(std::string(e.what()).find("16x64") != std::string::npos);
  }
  RangeImage bad = gt;
  bad.intensity.pop_back();
  CHECK_THROWS_AS(evaluate_view(s, bad, gt), Error);
  bad = gt;
  bad.range[10] = std::numeric_limits<float>::quiet_NaN();
  CHECK_THROWS_AS(evaluate_view(s, bad, gt), Error);
  CHECK_THROWS_AS(evaluate_view(s, gt, bad), Error);
}

TEST_CASE("mean_metrics averages per key and keeps null", "[metrics][evaluate]") {
  const Json a = {{"x", 1.0}, {"lp", nullptr}, {"y", 2.0}};
  const Json b = {{"x", 3.0}, {"lp", nullptr}, {"y", nullptr}};
  const Json m = mean_metrics({a, b});
  CHECK(m["x"].get<double>() == 2.0);
  CHECK(m["lp"].is_null());
  CHECK(m["y"].is_null());
  CHECK(mean_metrics({a})["y"].get<double>() == 2.0);
  CHECK_THROWS_AS(mean_metrics({a, Json{{"x", 1.0}, {"lp", nullptr}}}), Error);
  CHECK_THROWS_AS(mean_metrics({a, Json{{"x", "s"}, {"lp", nullptr}, {"y", 1.0}}}), Error);
  CHECK_THROWS_AS(mean_metrics({}), Error);
}

TEST_CASE("naive baseline: a test pose equal to a train pose reproduces that scan",
          "[metrics][baseline]") {
  const Sensor s = small_sensor();
  Rng rng(8);
  std::vector<std::vector<PointXYZI>> scans(3);
  for (auto& scan : scans)
    for (int i = 0; i < 2000; ++i) {
      const Eigen::Vector3f d =
          pixel_direction(s, int(rng.below(16)), int(rng.below(64))) * rng.uniform(3.f, 60.f);
      scan.push_back({d.x(), d.y(), d.z(), rng.uniform()});
    }
  std::vector<Pose> T_world_lidar;
  for (int k = 0; k < 3; ++k) {
    Vec6 xi;
    xi << 0.05 * k, -0.03, 0.7 * k, 10.0 * k, 2.0 * k, 0.1;
    T_world_lidar.push_back(exp_se3(xi));
  }
  const std::vector<const std::vector<PointXYZI>*> ptrs = {&scans[0], &scans[1], &scans[2]};
  const RangeImage out = naive_baseline_view(s, T_world_lidar, ptrs, T_world_lidar[1]);
  const RangeImage ref = project_points(s, scans[1]);
  size_t returns = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    REQUIRE(out.ray_drop[i] == ref.ray_drop[i]);
    REQUIRE(std::abs(out.range[i] - ref.range[i]) < 1e-4f);
    REQUIRE(out.intensity[i] == ref.intensity[i]);
    returns += ref.ray_drop[i] > 0;
  }
  CHECK(returns > 500);
  // Slightly off pose 2 → scan 2 is chosen.
  Pose near2 = T_world_lidar[2];
  near2.translation() += Vec3(0.5, -0.5, 0.0);
  CHECK(nearest_train_pose(T_world_lidar, near2) == 2);
  // The baseline's view evaluates like any prediction.
  const Json j = evaluate_view(s, out, ref);
  CHECK(j["cd"].get<double>() < 1e-8);
}

TEST_CASE("naive baseline moves points with the GT poses (by hand)", "[metrics][baseline]") {
  const Sensor s = small_sensor();
  const std::vector<PointXYZI> scan = {{10.f, 0.f, 0.f, 0.7f}};
  Pose T_test = Pose::Identity();
  T_test.translation() = Vec3(2.0, 0.0, 0.0);  // 2 m ahead of the train pose
  const RangeImage out = naive_baseline_view(s, {Pose::Identity()}, {&scan}, T_test);
  const RangeImage ref = project_points(s, {{8.f, 0.f, 0.f, 0.7f}});
  CHECK(out.range == ref.range);
  CHECK(out.intensity == ref.intensity);
  CHECK(out.ray_drop == ref.ray_drop);
  CHECK_THROWS_AS(naive_baseline_view(s, {Pose::Identity()}, {}, T_test), Error);
  CHECK_THROWS_AS(naive_baseline_view(s, {Pose::Identity()}, {nullptr}, T_test), Error);
}

TEST_CASE("the recorded metric definitions match the constants the metrics use", "[metrics]") {
  const Json d = metrics::definitions();
  CHECK(d.at("point_cloud").at("fscore_threshold_sq_m2").get<double>() == metrics::kFscoreThresholdSq);
  CHECK_THAT(d.at("pose").at("alignment").get<std::string>(), Catch::Contains("scale fixed to 1"));
  CHECK_THAT(d.at("raydrop_mask").get<std::string>(), Catch::Contains("predicted"));
  CHECK(d.at("depth").at("clip_m").at(1).get<double>() == 80.0);
  // The ATE the definitions describe is the one pose_metrics computes: an SE(3) copy of the
  // ground truth scores 0, a scaled one does not (no scale in the alignment).
  std::vector<Pose> gt, moved, scaled;
  for (int i = 0; i < 6; ++i) {
    Pose p = Pose::Identity();
    p.translation() = Eigen::Vector3d(2.0 * i, 0.3 * i * i, 0.1 * i);
    gt.push_back(p);
    Pose q = p;
    q.translation() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) * p.translation() +
                      Eigen::Vector3d(5, -2, 1);
    q.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    moved.push_back(q);
    Pose s = p;
    s.translation() *= 1.5;
    scaled.push_back(s);
  }
  CHECK(metrics::pose_metrics(moved, gt).at("ate_m").get<double>() < 1e-6);
  CHECK(metrics::pose_metrics(scaled, gt).at("ate_m").get<double>() > 0.5);
  // The horizontal ATE under the same alignment, and which ATE the reference supports: this gt
  // climbs 0.1 m a frame, so "3d".
  CHECK_THAT(d.at("pose").at("ate_h_m").get<std::string>(), Catch::Contains("same 3D alignment"));
  CHECK_THAT(d.at("pose").at("ate_reference").get<std::string>(), Catch::Contains("1e-6 m"));
  CHECK_THAT(d.at("pose").at("ate_reference").get<std::string>(), Catch::Contains("nuScenes"));
  CHECK(metrics::pose_metrics(moved, gt).at("ate_h_m").get<double>() < 1e-6);
  CHECK(metrics::pose_metrics(moved, gt).at("ate_reference") == "3d");
}
