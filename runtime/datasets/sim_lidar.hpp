// The simulated spinning LiDAR: one exact ray per (beam, azimuth) pixel direction (protocol §1),
// intensity from reflectance, incidence angle and range plus noise, and the ray-drop model
// (no hit or beyond range, grazing incidence, weak return, specular glass, random dropout).
// Noise comes from Philox keyed by (seed, frame, pixel): identical for any thread count.
#pragma once
#include <cstdint>
#include <vector>

#include "datasets/sim_scene.hpp"
#include "geometry/range_image.hpp"
#include "geometry/se3.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::sim {

struct LidarModel {
  double range_noise_m = 0.015;         // σ of the range noise (plus range_noise_rel · r)
  double range_noise_rel = 3e-4;
  double intensity_noise = 0.02;        // σ of additive intensity noise
  double grazing_cos = 0.035;           // cos(incidence) below which returns fade out
  double weak_power = 2.0e-4;           // ρ·cosθ·(10 m / r)² threshold of a detectable return
  double random_drop = 0.015;           // probability of a random dropout
  double glass_drop = 0.55;             // extra drop probability on glass (specular)
  double foliage_drop = 0.12;           // leaves: partial returns lost
  bool noise = true;                    // false: exact ranges and intensities, no random drop
};

// Per-cause counts of pixels without a return.
struct DropStats {
  size_t rays = 0, returns = 0, no_hit = 0, out_of_range = 0, grazing = 0, weak = 0, specular = 0,
         random = 0;
  void add(const DropStats& o);
  double drop_rate() const { return rays ? 1.0 - double(returns) / double(rays) : 0.0; }
};

// Casts every pixel of `s` from T_world_lidar; returns the returns as points in the LiDAR frame
// in row-major pixel order. `threads` ≤ 0 uses the hardware concurrency.
std::vector<PointXYZI> cast_scan(const Scene& scene, const Sensor& s, const Pose& T_world_lidar,
                                 const LidarModel& model, uint64_t seed, uint32_t frame,
                                 int threads = 0, DropStats* stats = nullptr);

}  // namespace sgnlf::sim
