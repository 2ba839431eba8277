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

// The estimated width is a multiple of this: the image strides of the training presets (every
// k-th column of a range image: 1, 2, 5, 10) then divide it, where a measured width such as
// 2 003 (a prime) has no divisor but 1 and would make such a sub-image the whole image. The
// rounding moves a ~2 000-column estimate by at most 0.25 %, less than the measurement's own
// spread (2 003 to 2 016 columns on subsets of ten KITTI HDL-64E scans).
constexpr int kWidthMultiple = 10;

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
// (360° over the median azimuth step within a beam, rounded to a multiple of kWidthMultiple)
// and min/max range (0.1 % / 99.9 % percentiles), then checks the fit. Throws Error naming the estimate that failed (rows,
// field of view, width) and the kept fraction; refuses a sensor covering less than
// min_azimuth_coverage_deg of azimuth ("give --sensor FILE").
SensorEstimate estimate_sensor(const std::vector<ScanSample>& scans, const SensorEstimateOptions& o = {});

// The fraction of the in-range points of `scans` that the projection onto `s` keeps (not out
// of its field of view); `in_range` receives their count.
double kept_fraction(const Sensor& s, const std::vector<ScanSample>& scans, size_t* in_range = nullptr);

// The preset ("kitti360", "nuscenes") an estimate matches, "" for none. The field of view
// and the azimuth resolution identify a head; the beam count is the estimate's least reliable
// part (lasers closer than the histogram's 0.2° peak spacing merge, smeared ones split: one
// KITTI HDL-64E gives 59 to 69 rows on subsets of ten scans, 61 on a 21-scan folder):
//  - rows within 1/8 of the preset's: half the smallest relative gap between the beam counts
//    spinning heads are made with (16, 32, 40, 64, 128: 32 → 40 is a quarter), so that no
//    other head's count is taken for the preset's;
//  - fov_up and fov each within 10 % of the preset's fov (2.69° for kitti360's 26.9°, 4° for
//    nuscenes' 40°): real lasers stray from their nominal elevations (KITTI's HDL-64E
//    shows its top beam at +3.1 to +3.9° for the nominal +2°), and the presets stay far apart
//    (8° of fov_up, 49 % of fov);
//  - a preset width no finer than the scans' azimuth resolution (estimated width >= 0.9 × the
//    preset's: the presets' widths are range-image resolutions, e.g. half the HDL-64E's
//    ~2 083 steps).
std::string matching_preset(const Sensor& estimate);

}  // namespace sgnlf
