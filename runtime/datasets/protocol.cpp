#include "datasets/protocol.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf {

Split protocol_split(int n_frames, const std::string& frequency) {
  if (n_frames <= 0) throw ConfigError("protocol_split: n_frames = " + std::to_string(n_frames));
  std::vector<char> test(size_t(n_frames), 0);
  if (frequency == "standard") {
    for (int i = 13; i < n_frames; i += 13) test[size_t(i)] = 1;  // protocol §3
  } else if (frequency == "low") {
    for (int i : {4, 12, 20})
      if (i < n_frames) test[size_t(i)] = 1;
  } else {
    throw ConfigError("protocol_split: frequency '" + frequency + "' (expected standard or low)");
  }
  Split s;
  for (int i = 0; i < n_frames; ++i) (test[size_t(i)] ? s.test : s.train).push_back(i);
  return s;
}

Split dynamic_split(int n_frames) {
  if (n_frames <= 0) throw ConfigError("dynamic_split: n_frames = " + std::to_string(n_frames));
  Split s;
  for (int i = 0; i < n_frames; ++i) (i % 10 == 0 && i > 0 && i < n_frames - 1 ? s.test : s.train).push_back(i);
  return s;
}

Split named_split(const std::string& split, int n_frames, const std::string& frequency) {
  if (split == "protocol") return protocol_split(n_frames, frequency);
  if (split == "dynamic") return dynamic_split(n_frames);
  throw ConfigError("split '" + split + "' (expected protocol or dynamic)");
}

SceneNormalization compute_normalization(const Dataset& d, const std::vector<Pose>& T_world_lidar,
                                         const std::vector<int>& frames) {
  require(T_world_lidar.size() == d.frames.size(),
          "compute_normalization: " + std::to_string(T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  const double inf = std::numeric_limits<double>::infinity();
  Vec3 lo(inf, inf, inf), hi(-inf, -inf, -inf);
  size_t used = 0;
  for (int f : frames) {
    require(f >= 0 && size_t(f) < d.frames.size(), "compute_normalization: frame " + std::to_string(f));
    const Pose& T = T_world_lidar[size_t(f)];
    for (const auto& p : d.frames[size_t(f)].points) {
      const Vec3 q(p.x, p.y, p.z);
      const double r = q.norm();
      if (!(r > d.sensor.min_range_m && r < d.sensor.max_range_m)) continue;
      const Vec3 w = T * q;
      lo = lo.cwiseMin(w);
      hi = hi.cwiseMax(w);
      ++used;
    }
  }
  if (used == 0) throw NumericError("compute_normalization: no points in range in the given frames");
  SceneNormalization n;
  n.center = 0.5 * (lo + hi);
  const double extent = (hi - n.center).cwiseAbs().maxCoeff();  // = max |centred coordinate|
  n.scale = extent > 0 ? 1.0 / extent : 1.0;
  return n;
}

std::vector<Pose> perturb_poses(const std::vector<Pose>& T_gt, uint64_t seed, double sigma_rot_rad,
                                double sigma_trans_m) {
  Rng rng(seed);
  std::vector<Pose> out;
  out.reserve(T_gt.size());
  for (const auto& T : T_gt) {
    Vec6 xi;
    for (int k = 0; k < 3; ++k) xi[k] = sigma_rot_rad * rng.normal();
    for (int k = 3; k < 6; ++k) xi[k] = sigma_trans_m * rng.normal();
    out.push_back(T * exp_se3_decoupled(xi));
  }
  return out;
}

std::vector<Pose> identity_poses(size_t n) { return std::vector<Pose>(n, Pose::Identity()); }

std::vector<Pose> gt_poses(const Dataset& d) {
  std::vector<Pose> p;
  for (const auto& f : d.frames) p.push_back(f.T_world_lidar);
  return p;
}

}  // namespace sgnlf
