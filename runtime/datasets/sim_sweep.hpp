// A sweep cast from a moving sensor (motion distortion): each azimuth step fires at
// its own time within the sweep (the sensor's per-point time model, geometry/sweep_timing.hpp)
// from the pose interpolated at that time, and its point is stored in the sensor frame of that
// moment, uncompensated, as a real spinning LiDAR delivers it; the frame's pose is the pose at
// the sweep's reference time. Moving objects move during the sweep too.
#pragma once
#include <functional>

#include "datasets/sim_lidar.hpp"

namespace sgnlf::sim {

// The sensor at the start and end of a sweep; in between it moves at a constant body-frame
// velocity: T(f) = T_start · Exp(f · Log(T_start⁻¹ T_end)), f ∈ [0, 1] the sweep fraction.
struct SweepPoses {
  Pose T_world_start = Pose::Identity(), T_world_end = Pose::Identity();
  Pose at(double fraction) const;
  // The constant velocity (rad/s, m/s, body frame) of a sweep lasting duration_s.
  Vec6 twist_per_s(double duration_s) const;
};

// Casts one sweep of the sensor's beam pattern, column by column from the pose at the column's
// sweep fraction (Sensor::sweep). `place_dynamic(fraction)`, when given, moves the scene's
// dynamic primitives to that moment of the sweep; it is called once per slice (of `slices`
// equal slices of the sweep, in time order) before the slice's columns are cast. `labels`,
// when given, receives each returned point's label (as cast_scan).
std::vector<PointXYZI> cast_sweep(Scene& scene, const Sensor& s, const SweepPoses& poses,
                                  const LidarModel& model, uint64_t seed, uint32_t frame,
                                  int threads = 0, DropStats* stats = nullptr,
                                  const std::function<void(double)>& place_dynamic = {},
                                  int slices = 72, std::vector<uint16_t>* labels = nullptr);

}  // namespace sgnlf::sim
