// Ground split and subsampling of the flow supervision's points (flow_points.hpp).
#include "pipeline/train/flow_points.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::pipeline {
namespace {

// Up to `k` of `pts`, drawn without replacement (a partial Fisher–Yates shuffle), in draw order.
std::vector<geometry::Point3f> subsample(std::vector<geometry::Point3f> pts, int k, Rng& rng) {
  const size_t n = std::min(pts.size(), size_t(std::max(k, 0)));
  for (size_t i = 0; i < n; ++i) {
    const size_t j = i + rng.below(uint32_t(pts.size() - i));
    std::swap(pts[i], pts[j]);
  }
  pts.resize(n);
  return pts;
}

}  // namespace

double ground_height(const std::vector<PointXYZI>& points, const FlowSupervisionConfig& c,
                     const std::string& what) {
  std::vector<double> z;
  const double r2 = c.ground_range_m * c.ground_range_m;
  for (const auto& p : points)
    if (double(p.x) * p.x + double(p.y) * p.y <= r2 && std::isfinite(p.z)) z.push_back(p.z);
  if (z.empty())
    throw Error(what + ": no return within " + std::to_string(c.ground_range_m) +
                " m of the sensor to find the ground from");
  // The lower half of the nearby returns, binned by height; the densest bin is the ground.
  std::sort(z.begin(), z.end());
  z.resize((z.size() + 1) / 2);
  const double lo = z.front(), bin = c.ground_bin_m;
  std::vector<int> count(size_t((z.back() - lo) / bin) + 1, 0);
  for (double v : z) ++count[size_t((v - lo) / bin)];
  const size_t best = size_t(std::max_element(count.begin(), count.end()) - count.begin());
  return lo + (double(best) + 0.5) * bin;
}

std::vector<FramePoints> flow_points(const Dataset& d, const Scene& scene,
                                     const FlowSupervisionConfig& c, uint64_t seed) {
  require(scene.T_world_lidar.size() == d.frames.size(),
          "flow_points: " + std::to_string(scene.T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  const float s = float(scene.norm.scale);
  std::vector<FramePoints> out(d.frames.size());
  for (size_t k = 0; k < d.frames.size(); ++k) {
    const Frame& fr = d.frames[k];
    const std::string what = d.name + " frame " + std::to_string(fr.id);
    const double z_ground = ground_height(fr.points, c, what) + c.ground_margin_m;
    const Eigen::Matrix3f R = scene.T_world_lidar[k].rotation().cast<float>();
    const Eigen::Vector3f t = scene.T_world_lidar[k].translation().cast<float>();
    std::vector<geometry::Point3f> moving, ground;
    for (const auto& p : fr.points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      const geometry::Point3f q = R * (geometry::Point3f(p.x, p.y, p.z) * s) + t;
      (double(p.z) <= z_ground ? ground : moving).push_back(q);
    }
    Rng rng(seed, uint32_t(k));
    out[k].moving = subsample(std::move(moving), c.points, rng);
    out[k].ground = subsample(std::move(ground), c.ground_points, rng);
  }
  return out;
}

}  // namespace sgnlf::pipeline
