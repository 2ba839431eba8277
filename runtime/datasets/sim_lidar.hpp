// The simulated spinning LiDAR: one exact ray per (beam, azimuth) pixel direction (protocol §1),
// intensity from reflectance, incidence angle and range plus noise, and the ray-drop model
// (no hit or beyond range, grazing incidence, weak return, specular glass, random dropout).
// Noise comes from Philox keyed by (seed, frame, pixel): identical for any thread count.
#pragma once
#include <cstdint>
#include <string>
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
  // intensity = gain · ρ · (ambient + (1 − ambient) · cos θ) · exp(−r / 250 m) + noise: KITTI's
  // reflectance is largely calibrated for incidence; nuScenes' 0–255 values are darker (gain).
  double intensity_ambient = 0.7;
  double intensity_gain = 1.0;
  double grazing_cos = 0.035;           // cos(incidence) below which returns fade out
  double weak_power = 2.0e-4;           // ρ·cosθ·(10 m / r)² threshold of a detectable return
  double random_drop = 0.015;           // probability of a random dropout
  double glass_drop = 0.55;             // extra drop probability on glass (specular)
  double foliage_drop = 0.12;           // leaves: partial returns lost
  bool noise = true;                    // false: exact ranges and intensities, no random drop
  // "native": the real sensor's laser elevations and azimuth steps (HDL-64E for kitti360,
  // HDL-32E for nuscenes), projected into the range image like real scans (empty rows where
  // beams are sparser than the grid, several returns per pixel); "grid": one ray per pixel.
  std::string beams = "native";
  bool ego_vehicle = true;  // rays blocked by the ego car's body return nothing
  // The ego car's body below the sensor (LiDAR frame: x forward): a box from ego_back_m behind
  // to ego_front_m ahead, ±ego_half_width_m, from the ground up to ego_top_m below the sensor.
  double ego_front_m = 1.4, ego_back_m = 2.4, ego_half_width_m = 0.9, ego_top_m = 1.0;
  // Real-scan ray drop (opt-in: 0 keeps every twin of the committed results bit for bit; the
  // real-like sequences set them, simulate.cpp). Their draws come from a separate Philox
  // stream, so the other causes see the same numbers with or without them.
  double beam_gain_sigma = 0.0;  // σ of log laser gain: some lasers of a real head are weaker
  double dark_drop = 0.0;        // drop probability on black surfaces, fading to 0 at ρ = 0.3
  double burst_drop = 0.0;       // probability that a block of burst_columns azimuth steps of
  int burst_columns = 12;        // one laser returns nothing (lost packets, dirt on the window)
  double far_drop = 0.0;         // drop probability rising linearly to this at max range
  bool realistic_drop() const {
    return beam_gain_sigma > 0 || dark_drop > 0 || burst_drop > 0 || far_drop > 0;
  }
  void validate() const;
};

// Laser elevations (degrees, top first) and azimuth steps per revolution of a sensor's beams.
struct BeamPattern {
  std::vector<double> elevation_deg;
  int azimuth_steps = 0;
  bool grid = false;  // one ray per range-image pixel
};
// "native" patterns exist for the kitti360 (HDL-64E) and nuscenes (HDL-32E) sensors; other
// sensors (user-defined) use the grid.
BeamPattern beam_pattern(const Sensor& s, const std::string& beams);

// Per-cause counts of pixels without a return (dark, burst, far: the real-scan causes).
struct DropStats {
  size_t rays = 0, returns = 0, no_hit = 0, out_of_range = 0, grazing = 0, weak = 0, specular = 0,
         random = 0, ego = 0, dark = 0, burst = 0, far = 0;
  void add(const DropStats& o);
  double drop_rate() const { return rays ? 1.0 - double(returns) / double(rays) : 0.0; }
};

// Casts every beam of the pattern from T_world_lidar; returns the returns as points in the
// LiDAR frame (laser-major order). Counts are per ray (the range image's drop rate is
// measured on the projected image). `threads` ≤ 0 uses the hardware concurrency. `labels`,
// when given, receives each returned point's label (Hit::label: 0 static, k actor k).
std::vector<PointXYZI> cast_scan(const Scene& scene, const Sensor& s, const Pose& T_world_lidar,
                                 const LidarModel& model, uint64_t seed, uint32_t frame,
                                 int threads = 0, DropStats* stats = nullptr,
                                 std::vector<uint16_t>* labels = nullptr);

// The building blocks of cast_scan and of the moving sweep (sim_sweep.hpp).
struct RayReturn {
  bool ret = false;
  PointXYZI p{0, 0, 0, 0};  // in the LiDAR frame of the ray's own pose
  uint16_t label = 0;       // what the return hit (Hit::label)
};
// Unit direction of laser `row` at azimuth step `col` in the LiDAR frame (protocol §1's β).
Eigen::Vector3f beam_direction(const Sensor& s, const BeamPattern& bp, int row, int col);
// Casts every row of the given columns, column col from T_world_lidar_of_column[col], into
// out[row · azimuth_steps + col] (out sized rows × azimuth_steps). Rows are split between
// threads; each ray's noise depends on (seed, frame, pixel) only.
void cast_columns(const Scene& scene, const Sensor& s, const BeamPattern& bp, const LidarModel& model,
                  uint64_t seed, uint32_t frame, const std::vector<int>& columns,
                  const std::vector<Pose>& T_world_lidar_of_column, int threads,
                  std::vector<RayReturn>& out, DropStats& stats);
// The returns of `rays` in laser-major order, and their labels in the same order.
std::vector<PointXYZI> collect_returns(const std::vector<RayReturn>& rays);
std::vector<uint16_t> collect_labels(const std::vector<RayReturn>& rays);

}  // namespace sgnlf::sim
