// The error anatomy (metrics/anatomy.hpp) on small hand-built range images whose answer is
// known, and on random ones where its parts must add up to evaluate_view's CD terms and depth MSE.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "metrics/anatomy.hpp"
#include "metrics/anatomy_json.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/image_metrics.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;

namespace {

Sensor tiny_sensor() {
  Sensor s = sensor_preset("kitti360");
  s.name = "tiny";
  s.height = 8;
  s.width = 32;
  return s;
}

// Every pixel returns at 12 m except the dropped column 0; predicted = ground truth.
RangeImage flat_gt(const Sensor& s) {
  RangeImage img(s.height, s.width);
  for (int r = 0; r < s.height; ++r)
    for (int c = 1; c < s.width; ++c) {
      img.range[img.idx(r, c)] = 12.f;
      img.intensity[img.idx(r, c)] = 0.5f;
      img.ray_drop[img.idx(r, c)] = 1.f;
    }
  return img;
}

RangeImage as_prediction(const RangeImage& gt) {
  RangeImage p = gt;
  for (size_t i = 0; i < p.size(); ++i) p.ray_drop[i] = gt.ray_drop[i] > 0.f ? 0.9f : 0.2f;
  return p;
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

void check_parts_add_up(const ErrorSplit& s, bool with_train) {
  const double tol = 1e-9 * std::max(1.0, std::abs(s.total));
  double by_cause = 0.0, by_band = 0.0, by_train = 0.0;
  for (int c = 0; c < kAnatomyCauses; ++c) by_cause += s.cause(c);
  for (int b = 0; b < kAnatomyRangeBands; ++b) by_band += s.band(b);
  for (double v : s.by_train) by_train += v;
  CHECK(by_cause == Approx(s.total).margin(tol));
  CHECK(by_band == Approx(s.total).margin(tol));
  CHECK(sum(s.by_row) == Approx(s.total).margin(tol));
  if (with_train) CHECK(by_train == Approx(s.total).margin(tol));
  else CHECK(std::isnan(by_train));
}

}  // namespace

TEST_CASE("anatomy bands: edges belong to the upper band", "[metrics][anatomy]") {
  CHECK(anatomy_range_band(0.0) == 0);
  CHECK(anatomy_range_band(9.99) == 0);
  CHECK(anatomy_range_band(10.0) == 1);
  CHECK(anatomy_range_band(30.0) == 2);
  CHECK(anatomy_range_band(79.9) == 3);
  CHECK(anatomy_range_band(80.0) == 4);
  CHECK(anatomy_range_band(300.0) == 4);
  CHECK(anatomy_train_band(0.05) == 0);
  CHECK(anatomy_train_band(0.1) == 1);
  CHECK(anatomy_train_band(1.0) == 2);
  CHECK(anatomy_train_band(2.0) == 3);
  CHECK(anatomy_train_band(std::numeric_limits<double>::infinity()) == 3);
}

TEST_CASE("a perfect prediction has no error in any part", "[metrics][anatomy]") {
  const Sensor s = tiny_sensor();
  const RangeImage gt = flat_gt(s);
  const ViewAnatomy a = view_anatomy(s, as_prediction(gt), gt);
  for (const ErrorSplit* q : {&a.cd_pred_to_gt, &a.cd_gt_to_pred, &a.depth_mse}) {
    CHECK(q->total == 0.0);
    for (const auto& c : q->by_cause_range)
      for (double v : c) CHECK(v == 0.0);
    for (double v : q->by_row) CHECK(v == 0.0);
  }
  CHECK(a.pixels[kCauseBoth][1] == Approx(double(s.height * (s.width - 1)) / (s.height * s.width)));
  CHECK(a.pixels[kCauseFalse][2] == 0.0);
  CHECK(a.n_pred == a.n_gt);
}

TEST_CASE("a false return at 30 m lands in the 20-40 m band as a false return", "[metrics][anatomy]") {
  const Sensor s = tiny_sensor();
  const RangeImage gt = flat_gt(s);
  RangeImage pred = as_prediction(gt);
  const size_t i = gt.idx(3, 0);  // column 0 is dropped in the ground truth
  pred.range[i] = 30.f;
  pred.ray_drop[i] = 0.8f;
  const ViewAnatomy a = view_anatomy(s, pred, gt);
  const double n = double(gt.size());
  // Depth: (30 − 1e-6)² over all pixels, all of it false returns at 20–40 m in row 3.
  const double e = std::pow(30.0 - 1e-6, 2) / n;
  CHECK(a.depth_mse.total == Approx(e).epsilon(1e-12));
  CHECK(a.depth_mse.by_cause_range[kCauseFalse][2] == Approx(e).epsilon(1e-12));
  CHECK(a.depth_mse.cause(kCauseBoth) == 0.0);
  CHECK(a.depth_mse.by_row[3] == Approx(e).epsilon(1e-12));
  CHECK(a.pixels[kCauseFalse][2] == Approx(1.0 / n));
  // pred → GT: only the false point is away from the ground truth; nearest GT point is 18 m
  // nearer along a neighbouring ray at least, so its squared distance is > 0 and all of the
  // direction's error is the false return's, in the 20–40 m band.
  CHECK(a.cd_pred_to_gt.total > 0.0);
  CHECK(a.cd_pred_to_gt.by_cause_range[kCauseFalse][2] == Approx(a.cd_pred_to_gt.total));
  CHECK(a.cd_pred_to_gt.cause(kCauseBoth) == 0.0);
  // GT → pred is untouched: every ground-truth point has its own predicted twin.
  CHECK(a.cd_gt_to_pred.total == 0.0);
  CHECK(a.pixel_case[i] == uint8_t(ReturnCase::false_return));
  check_parts_add_up(a.cd_pred_to_gt, false);
}

TEST_CASE("a missed return at 15 m is a missed return in the 10-20 m band", "[metrics][anatomy]") {
  const Sensor s = tiny_sensor();
  const RangeImage gt = flat_gt(s);
  RangeImage pred = as_prediction(gt);
  const size_t i = gt.idx(5, 7);
  pred.ray_drop[i] = 0.3f;  // the prediction drops a ray the sensor returned (12 m)
  const ViewAnatomy a = view_anatomy(s, pred, gt);
  const double e = std::pow(12.0 - 1e-6, 2) / double(gt.size());
  CHECK(a.depth_mse.by_cause_range[kCauseMissed][1] == Approx(e).epsilon(1e-12));
  CHECK(a.depth_mse.total == Approx(e).epsilon(1e-12));
  CHECK(a.cd_gt_to_pred.total > 0.0);
  CHECK(a.cd_gt_to_pred.by_cause_range[kCauseMissed][1] == Approx(a.cd_gt_to_pred.total));
  CHECK(a.cd_pred_to_gt.total == 0.0);
  CHECK(a.pixel_case[i] == uint8_t(ReturnCase::missed));
}

TEST_CASE("the parts add up to evaluate_view's CD terms and depth MSE", "[metrics][anatomy]") {
  Sensor s = tiny_sensor();
  s.height = 16;
  s.width = 64;
  Rng rng(11);
  RangeImage gt(s.height, s.width), pred(s.height, s.width);
  for (size_t i = 0; i < gt.size(); ++i) {
    if (rng.uniform() > 0.25f) {
      gt.range[i] = rng.uniform(2.f, 95.f);
      gt.ray_drop[i] = 1.f;
      gt.intensity[i] = rng.uniform();
    }
    pred.intensity[i] = rng.uniform();
    pred.range[i] = std::max(0.5f, (gt.range[i] > 0 ? gt.range[i] : 40.f) + rng.uniform(-3.f, 3.f));
    pred.ray_drop[i] = rng.uniform();
  }
  const Json m = evaluate_view(s, pred, gt);
  const ViewAnatomy a = view_anatomy(s, pred, gt);
  CHECK(a.cd_pred_to_gt.total == Approx(m["cd_pred_to_gt"].get<double>()).epsilon(1e-12));
  CHECK(a.cd_gt_to_pred.total == Approx(m["cd_gt_to_pred"].get<double>()).epsilon(1e-12));
  CHECK(a.depth_mse.total == Approx(std::pow(m["depth_rmse"].get<double>(), 2)).epsilon(1e-9));
  CHECK(a.depth_mse.cause(kCauseBoth) == Approx(m["depth_mse_returns"].get<double>()).epsilon(1e-12));
  CHECK(a.depth_mse.cause(kCauseMissed) == Approx(m["depth_mse_missed"].get<double>()).epsilon(1e-12));
  CHECK(a.depth_mse.cause(kCauseFalse) == Approx(m["depth_mse_false"].get<double>()).epsilon(1e-12));
  // Every cause and band is populated here, so a mis-binned part would show.
  for (int c : {kCauseBoth, kCauseMissed, kCauseFalse}) CHECK(a.depth_mse.cause(c) > 0.0);
  for (int b = 0; b < kAnatomyRangeBands; ++b) CHECK(a.depth_mse.band(b) > 0.0);
  CHECK(a.cd_pred_to_gt.cause(kCauseMissed) == 0.0);
  CHECK(a.cd_gt_to_pred.cause(kCauseFalse) == 0.0);
  for (const ErrorSplit* q : {&a.cd_pred_to_gt, &a.cd_gt_to_pred, &a.depth_mse})
    check_parts_add_up(*q, false);
  double pix = 0.0;
  for (const auto& c : a.pixels)
    for (double v : c) pix += v;
  // Shares of the pixels where either side returns: all but the true drops.
  const auto neither = std::count(a.pixel_case.begin(), a.pixel_case.end(), uint8_t(ReturnCase::neither));
  CHECK(neither > 0);
  CHECK(pix == Approx(1.0 - double(neither) / double(gt.size())));

  // With the training points: the ground truth itself, in a world frame 5 m away, so every
  // ground-truth point is at distance 0 and a false return's distance is its gap to them.
  Pose T_world_lidar = Pose::Identity();
  T_world_lidar.translation() = Vec3(5.0, -2.0, 1.0);
  std::vector<geometry::Point3f> train_world;
  for (int r = 0; r < s.height; ++r)
    for (int c = 0; c < s.width; ++c)
      if (gt.ray_drop[gt.idx(r, c)] > 0)
        train_world.push_back(T_world_lidar.cast<float>() * (pixel_direction(s, r, c) * gt.range[gt.idx(r, c)]));
  const geometry::KdTree tree(train_world);
  const TrainingPoints tp{&tree, T_world_lidar};
  const ViewAnatomy at = view_anatomy(s, pred, gt, &tp);
  for (const ErrorSplit* q : {&at.cd_pred_to_gt, &at.cd_gt_to_pred, &at.depth_mse})
    check_parts_add_up(*q, true);
  // GT → pred: every point is a training point (band <0.1 m); the same total as without.
  CHECK(at.cd_gt_to_pred.by_train[0] == Approx(at.cd_gt_to_pred.total).epsilon(1e-12));
  CHECK(at.cd_gt_to_pred.total == a.cd_gt_to_pred.total);
  // Depth: false returns lie off the ground truth (beyond 0.1 m), everything else on it.
  CHECK(at.depth_mse.by_train[0] == Approx(at.depth_mse.cause(kCauseBoth) + at.depth_mse.cause(kCauseMissed)).epsilon(1e-9));

  const TrainingPoints bad{nullptr, T_world_lidar};
  CHECK_THROWS_WITH(view_anatomy(s, pred, gt, &bad), Catch::Contains("training points"));
}

TEST_CASE("anatomy refuses mismatched images naming the sizes", "[metrics][anatomy]") {
  const Sensor s = tiny_sensor();
  const RangeImage gt = flat_gt(s);
  const RangeImage small(4, 32);
  CHECK_THROWS_WITH(view_anatomy(s, small, gt),
                    Catch::Contains("view_anatomy: predicted image is 4x32") &&
                        Catch::Contains("is 8x32"));
  CHECK_THROWS_WITH(view_anatomy(s, as_prediction(gt), small),
                    Catch::Contains("ground-truth image is 4x32"));
  RangeImage half = gt;
  half.ray_drop[3] = 0.5f;
  CHECK_THROWS_WITH(view_anatomy(s, as_prediction(gt), half), Catch::Contains("expected 0 or 1"));
}

TEST_CASE("anatomy JSON: fixed keys, means that add up, shares", "[metrics][anatomy]") {
  const Sensor s = tiny_sensor();
  const RangeImage gt = flat_gt(s);
  RangeImage p1 = as_prediction(gt), p2 = as_prediction(gt);
  p1.range[gt.idx(2, 0)] = 30.f, p1.ray_drop[gt.idx(2, 0)] = 0.9f;  // a false return
  p2.ray_drop[gt.idx(6, 9)] = 0.1f;                                  // a missed one
  p2.range[gt.idx(1, 4)] = 13.f;                                     // a range error
  const Json j1 = anatomy_json(view_anatomy(s, p1, gt));
  const Json j2 = anatomy_json(view_anatomy(s, p2, gt));
  std::set<std::string> k1, k2;
  for (const auto& [k, v] : j1.items()) k1.insert(k);
  for (const auto& [k, v] : j2.items()) k2.insert(k);
  CHECK(k1 == k2);
  // Per quantity: total, causes × (1 + 5 bands), 5 bands, 8 rows, 4 train bands.
  CHECK(k1.size() == (1 + 2 * 6 + 5 + 8 + 4) * 2 + (1 + 3 * 6 + 5 + 8 + 4) + 15 + 2);
  CHECK(j1.at("cd_pred_to_gt/train/<0.1m").is_null());
  CHECK(j1.at("cd_pred_to_gt/row/002").get<double>() > 0.0);
  CHECK_FALSE(j1.contains("cd_pred_to_gt/cause/missed"));
  const Json mean = mean_metrics({j1, j2});
  CHECK(mean.at("depth_mse/total").get<double>() ==
        Approx(mean.at("depth_mse/cause/both").get<double>() +
               mean.at("depth_mse/cause/missed").get<double>() +
               mean.at("depth_mse/cause/false").get<double>()));
  const auto rows = anatomy_shares(mean, j1);
  REQUIRE(rows.size() == 1 + 3 + 5);  // no train rows without training points
  CHECK(rows[0].split == "total");
  CHECK(rows[0].model[2] == mean.at("depth_mse/total").get<double>());
  double causes = 0.0;
  for (size_t r = 1; r <= 3; ++r) causes += rows[r].model[2];
  CHECK(causes == Approx(1.0));
  CHECK(std::isnan(rows[2].model[0]));  // pred → GT has no missed part
  CHECK(rows[3].baseline[2] == Approx(1.0));  // view 1's depth error is all false returns
  CHECK_THROWS_WITH(anatomy_shares(Json::object(), j1), Catch::Contains("model anatomy has no key"));
}
