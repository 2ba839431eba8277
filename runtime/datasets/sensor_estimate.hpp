// Estimating the sensor of a plain folder of scans that says nothing about it (issue "Your own
// scans", part 2): beams, their elevations, the azimuth resolution and the range limits from a
// sample of the scans, then a check that the range image of the estimate keeps the points
// (protocol §1 projection). Deterministic: the same scans give the same sensor.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "geometry/range_image.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf {

// One scan in the sensor frame; `ring` is empty or holds each point's laser index.
struct ScanSample {
  std::vector<PointXYZI> points;
  std::vector<int32_t> ring;
};

struct SensorEstimateOptions {
  double min_kept_fraction = 0.95;        // of the in-range points, inside the field of view
  double min_azimuth_coverage_deg = 300;  // below: not a spinning 360° sensor, refused
  double rate_hz = 10.0;                  // scans have no clock: the caller's rate
  // Test hook: changes the estimate before the check (forces a wrong estimate in the tests).
  std::function<void(Sensor&)> adjust;
};

struct SensorEstimate {
  Sensor sensor;                        // name "estimated"
  bool from_rings = false;              // beams from the ring field, else elevation histogram peaks
  std::vector<double> beam_elevation_deg;  // one per beam found, top first
  double azimuth_coverage_deg = 0.0;
  size_t in_range_points = 0;           // of the sample, under the estimated range limits
  double kept_fraction = 0.0;           // of those, inside the estimate's field of view
};

// Up to `max_scans` of `files` (evenly spread, first and last included), read with their rings
// when the format has them.
std::vector<ScanSample> read_scan_sample(const std::vector<std::string>& files, int max_scans = 8);

// Estimates rows (the ring field's beam count, else the peaks of the elevation histogram),
// fov_up_deg / fov_deg (the top and bottom beams, one row step apart at the ends), width
// (360° over the median azimuth step within a beam) and min/max range (0.1 % / 99.9 %
// percentiles), then checks the fit. Throws Error naming the estimate that failed (rows,
// field of view, width) and the kept fraction; refuses a sensor covering less than
// min_azimuth_coverage_deg of azimuth ("give --sensor FILE").
SensorEstimate estimate_sensor(const std::vector<ScanSample>& scans, const SensorEstimateOptions& o = {});

// The fraction of the in-range points of `scans` that the projection onto `s` keeps (not out
// of its field of view); `in_range` receives their count.
double kept_fraction(const Sensor& s, const std::vector<ScanSample>& scans, size_t* in_range = nullptr);

// The preset ("kitti360", "nuscenes") an estimate matches, "" for none: the same beam count
// within max(2, 5 %), fov_up within 2° and fov within 10 % (real heads' lasers stray from their
// nominal elevations: KITTI's HDL-64E shows beams up to +3.9°), and a preset width no finer
// than the scans' azimuth resolution (estimated width >= 0.9 × the preset's: the presets'
// widths are range-image resolutions, e.g. half the HDL-64E's ~2 083 steps).
std::string matching_preset(const Sensor& estimate);

}  // namespace sgnlf
