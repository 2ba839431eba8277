// Simulated scans shared by the odometry tests (each sequence simulated once per binary).
#pragma once
#include "datasets/simulate.hpp"
#include "odometry/trajectory.hpp"

namespace sgnlf::test {

// The named synthetic sequence at full sensor resolution, its first `frames` frames.
inline Dataset simulated(const std::string& sequence, int frames) {
  SimOptions o;
  o.sequence = sequence;
  o.frames = frames;
  o.threads = 2;
  return simulate_dataset(o);
}

inline const Dataset& kitti360_low() {
  static const Dataset d = simulated("kitti360-low-a", 16);
  return d;
}
inline const Dataset& nuscenes_low() {
  static const Dataset d = simulated("nuscenes-low-a", 16);
  return d;
}

}  // namespace sgnlf::test
