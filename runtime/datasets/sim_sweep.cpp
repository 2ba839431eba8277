// cast_sweep (see sim_sweep.hpp).
#include "datasets/sim_sweep.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "geometry/deskew.hpp"

namespace sgnlf::sim {

Pose SweepPoses::at(double fraction) const {
  return T_world_start * exp_se3(fraction * log_se3(T_world_start.inverse() * T_world_end));
}

Vec6 SweepPoses::twist_per_s(double duration_s) const {
  return constant_velocity_twist(T_world_start, T_world_end, duration_s);
}

std::vector<PointXYZI> cast_sweep(Scene& scene, const Sensor& s, const SweepPoses& poses,
                                  const LidarModel& model, uint64_t seed, uint32_t frame, int threads,
                                  DropStats* stats, const std::function<void(double)>& place_dynamic,
                                  int slices, std::vector<uint16_t>* labels) {
  require(slices >= 1, "cast_sweep: slices = " + std::to_string(slices));
  const BeamPattern bp = beam_pattern(s, model.beams);
  const int rows = int(bp.elevation_deg.size()), cols = bp.azimuth_steps;
  // Each column fires at the sweep fraction of its azimuth (every laser of a column shares it).
  std::vector<Pose> T_col(static_cast<size_t>(cols));
  std::vector<std::vector<int>> slice_cols(static_cast<size_t>(slices));
  for (int c = 0; c < cols; ++c) {
    const Eigen::Vector3f d = beam_direction(s, bp, 0, c);
    const double f = sweep_fraction(s.sweep, d.cast<double>());
    T_col[size_t(c)] = poses.at(f);
    slice_cols[size_t(std::min(slices - 1, int(f * slices)))].push_back(c);
  }
  std::vector<RayReturn> px(size_t(rows) * cols);
  DropStats st;
  for (int k = 0; k < slices; ++k) {
    if (slice_cols[size_t(k)].empty()) continue;
    if (place_dynamic) place_dynamic((k + 0.5) / slices);
    cast_columns(scene, s, bp, model, seed, frame, slice_cols[size_t(k)], T_col, threads, px, st);
  }
  if (stats) stats->add(st);
  if (labels) *labels = collect_labels(px);
  return collect_returns(px);
}

}  // namespace sgnlf::sim
