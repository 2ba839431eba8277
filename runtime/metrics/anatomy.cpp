// view_anatomy (see anatomy.hpp).
#include "metrics/anatomy.hpp"

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "metrics/chamfer.hpp"
#include "metrics/image_metrics.hpp"
#include "metrics/masked_view.hpp"

namespace sgnlf::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Sums of one quantity's contributions per bin; normalised once at the end.
struct Accumulator {
  ErrorSplit s;
  explicit Accumulator(int height) { s.by_row.assign(size_t(height), 0.0); }
  void add(double v, int cause, int band, int row, int train_band) {
    s.by_cause_range[size_t(cause)][size_t(band)] += v;
    s.by_row[size_t(row)] += v;
    s.by_train[size_t(train_band)] += v;
    s.total += v;
  }
  ErrorSplit finish(double count, bool has_train) {
    const double k = count > 0.0 ? 1.0 / count : kNaN;
    s.total *= k;
    for (auto& c : s.by_cause_range)
      for (double& v : c) v *= k;
    for (double& v : s.by_row) v *= k;
    for (double& v : s.by_train) v = has_train ? v * k : kNaN;
    return s;
  }
};

// Distance (m) from each pixel's point (the ground truth's where it has one, else the
// prediction's) to the nearest training point; +∞ for a pixel without a point.
std::vector<double> train_distance(const Sensor& s, const MaskedView& v, const TrainingPoints& t) {
  std::vector<double> dist(v.depth.size(), std::numeric_limits<double>::infinity());
  const Eigen::Isometry3f T = t.T_world_lidar.cast<float>();
  for (int r = 0; r < s.height; ++r)
    for (int c = 0; c < s.width; ++c) {
      const size_t i = size_t(r) * s.width + c;
      const float range = v.gt_depth[i] != 0.f ? v.gt_depth[i] : v.depth[i];
      if (range == 0.f) continue;
      const geometry::Point3f p_world = T * (pixel_direction(s, r, c) * range);
      dist[i] = std::sqrt(double(t.points_world->nearest(p_world)));
    }
  return dist;
}

}  // namespace

const std::array<std::string, kAnatomyCauses>& anatomy_cause_names() {
  static const std::array<std::string, kAnatomyCauses> n = {"both", "missed", "false"};
  return n;
}
const std::array<std::string, kAnatomyRangeBands>& anatomy_range_band_names() {
  static const std::array<std::string, kAnatomyRangeBands> n = {"0-10m", "10-20m", "20-40m",
                                                                "40-80m", "80m+"};
  return n;
}
const std::array<std::string, kAnatomyTrainBands>& anatomy_train_band_names() {
  static const std::array<std::string, kAnatomyTrainBands> n = {"<0.1m", "0.1-0.5m", "0.5-2m",
                                                                "2m+"};
  return n;
}

int anatomy_range_band(double range_m) {
  int b = 0;
  while (b < int(kAnatomyRangeEdgesM.size()) && range_m >= kAnatomyRangeEdgesM[size_t(b)]) ++b;
  return b;
}

int anatomy_train_band(double distance_m) {
  int b = 0;
  while (b < int(kAnatomyTrainEdgesM.size()) && distance_m >= kAnatomyTrainEdgesM[size_t(b)]) ++b;
  return b;
}

double ErrorSplit::cause(int c) const {
  double sum = 0.0;
  for (double v : by_cause_range[size_t(c)]) sum += v;
  return sum;
}

double ErrorSplit::band(int b) const {
  double sum = 0.0;
  for (const auto& c : by_cause_range) sum += c[size_t(b)];
  return sum;
}

ViewAnatomy view_anatomy(const Sensor& sensor, const RangeImage& pred, const RangeImage& gt,
                         const TrainingPoints* train) {
  const MaskedView v = mask_view(sensor, pred, gt, "view_anatomy");
  raydrop_metrics(pred.ray_drop, gt.ray_drop);  // refuses labels other than 0 and 1
  if (train) {
    require(train->points_world && train->points_world->size() > 0,
            "view_anatomy: the training points are missing or empty");
    require(train->T_world_lidar.matrix().allFinite(), "view_anatomy: the view's pose is not finite");
  }
  const size_t n = pred.size();
  const int width = sensor.width;
  const std::vector<double> dist =
      train ? train_distance(sensor, v, *train) : std::vector<double>(n, 0.0);
  auto band_of = [&](size_t i) {
    return anatomy_range_band(double(v.gt_depth[i] != 0.f ? v.gt_depth[i] : v.depth[i]));
  };
  auto train_of = [&](size_t i) { return train ? anatomy_train_band(dist[i]) : 0; };

  ViewAnatomy a;
  a.has_train = train != nullptr;
  a.pixel_case.resize(n);
  // Depth MSE: every pixel's squared clipped error, by its return decisions.
  Accumulator depth(sensor.height);
  for (size_t i = 0; i < n; ++i) {
    const ReturnCase rc = return_case(pred.ray_drop[i], gt.ray_drop[i]);
    a.pixel_case[i] = uint8_t(rc);
    if (rc == ReturnCase::neither) continue;  // both masked to 0: no error (DepthErrorParts)
    const int cause = rc == ReturnCase::both ? kCauseBoth
                      : rc == ReturnCase::missed ? kCauseMissed : kCauseFalse;
    depth.add(depth_sq_error(v.depth[i], v.gt_depth[i]), cause, band_of(i), int(i) / width,
              train_of(i));
    a.pixels[size_t(cause)][size_t(band_of(i))] += 1.0 / double(n);
  }
  a.depth_mse = depth.finish(double(n), a.has_train);

  // CD: each point's squared NN distance to the other cloud (chamfer.hpp), by whether the other
  // image has a point at the same pixel.
  std::vector<uint32_t> pix_pred, pix_gt;
  const auto pts_pred = to_points_lidar(sensor, v.depth, &pix_pred);
  const auto pts_gt = to_points_lidar(sensor, v.gt_depth, &pix_gt);
  a.n_pred = pts_pred.size();
  a.n_gt = pts_gt.size();
  Accumulator p2g(sensor.height), g2p(sensor.height);
  if (!pts_pred.empty() && !pts_gt.empty()) {
    const NearestSquaredDistances d = nearest_squared_distances(pts_pred, pts_gt);
    for (size_t k = 0; k < pts_pred.size(); ++k) {
      const size_t i = pix_pred[k];
      p2g.add(double(d.pred_to_gt[k]), v.gt_depth[i] != 0.f ? kCauseBoth : kCauseFalse,
              band_of(i), int(i) / width, train_of(i));
    }
    for (size_t k = 0; k < pts_gt.size(); ++k) {
      const size_t i = pix_gt[k];
      g2p.add(double(d.gt_to_pred[k]), v.depth[i] != 0.f ? kCauseBoth : kCauseMissed,
              band_of(i), int(i) / width, train_of(i));
    }
  }
  // Empty clouds: CD is undefined (evaluate_view's null), and so are its parts.
  const bool defined = !pts_pred.empty() && !pts_gt.empty();
  a.cd_pred_to_gt = p2g.finish(defined ? double(a.n_pred) : 0.0, a.has_train);
  a.cd_gt_to_pred = g2p.finish(defined ? double(a.n_gt) : 0.0, a.has_train);
  return a;
}

}  // namespace sgnlf::metrics
