// Test fixture for the confidence-aware pose graph: a small simulated kitti360-loop (36 frames
// at 2 Hz around a block; frames 31–35 revisit 0–4), its frame clouds, and the ground-truth
// overlap of two frames:
//   overlap(i → j) = fraction of frame i's cloud points (the FrameCloud subsample) whose nearest
//                    neighbour among ALL of frame j's simulated returns, under the ground-truth
//                    poses, lies within 0.5 m;
//   overlap(i, j)  = min(overlap(i → j), overlap(j → i))   (both frames see ≥ x % of each other).
#pragma once
#include <memory>
#include <vector>

#include "datasets/protocol.hpp"
#include "datasets/simulate.hpp"
#include "posegraph/frame_cloud.hpp"

namespace sgnlf::test {

// 36 frames, one ray per pixel of a 66 × 512 grid (simulated once per test binary).
inline const Dataset& loop_sequence() {
  static const Dataset d = [] {
    SimOptions o;
    o.sequence = "kitti360-loop";
    o.width = 512;
    o.lidar.beams = "grid";
    o.threads = 2;
    return simulate_dataset(o);
  }();
  return d;
}

inline std::vector<std::vector<PointXYZI>> loop_scans() {
  std::vector<std::vector<PointXYZI>> s;
  for (const auto& f : loop_sequence().frames) s.push_back(f.points);
  return s;
}

inline std::shared_ptr<const std::vector<posegraph::FrameCloud>> loop_clouds(size_t points) {
  return std::make_shared<const std::vector<posegraph::FrameCloud>>(
      posegraph::make_frame_clouds(loop_scans(), points, 1));
}

// overlap(i, j) for every pair (i < j) as a symmetric matrix (diagonal 1).
inline std::vector<std::vector<double>> gt_overlap(const std::vector<posegraph::FrameCloud>& clouds,
                                                   float radius_m = 0.5f) {
  const Dataset& d = loop_sequence();
  const auto gt = gt_poses(d);
  const size_t n = clouds.size();
  std::vector<geometry::KdTree> full;
  for (const auto& f : d.frames) {
    std::vector<geometry::Point3f> p;
    for (const auto& q : f.points) p.emplace_back(q.x, q.y, q.z);
    full.emplace_back(p);
  }
  auto directed = [&](size_t i, size_t j) {
    const Pose T_ji = gt[j].inverse() * gt[i];
    size_t hit = 0;
    for (const auto& p : clouds[i].points) {
      const geometry::Point3f q = (T_ji * p.cast<double>()).cast<float>();
      hit += full[j].nearest(q) <= radius_m * radius_m;
    }
    return double(hit) / double(clouds[i].size());
  };
  std::vector<std::vector<double>> o(n, std::vector<double>(n, 1.0));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) o[i][j] = o[j][i] = std::min(directed(i, j), directed(j, i));
  return o;
}

}  // namespace sgnlf::test
