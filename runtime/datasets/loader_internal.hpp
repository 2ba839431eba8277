// Shared pieces of the per-layout loaders (internal to the datasets module).
#pragma once
#include <string>
#include <vector>

#include "datasets/loader.hpp"

namespace sgnlf::detail {

// Frame ids `start, start+stride, ...` (up to `count`) among `available` (sorted); missing ids
// are skipped and counted in the log. Throws IoError when none is found.
std::vector<int> select_window(const std::vector<int>& available, int start, int stride, int count,
                               const std::string& where);

// Resolved defaults for a frequency: stride (from the native rate `rate_hz`: opt.rate_hz wanted,
// else 2 Hz for low, else 1) and frame count.
int default_stride(const LoadOptions& opt, const std::string& frequency, double rate_hz);
int default_count(const LoadOptions& opt, const std::string& frequency);
// opt.frequency, else the class of opt.rate_hz when set (frequency_class), else `fallback`.
std::string resolve_frequency(const LoadOptions& opt, const std::string& fallback);
Sensor resolve_sensor(const LoadOptions& opt, const Sensor& layout_default);

// Reads the scan, projects it into `f.image` and keeps in `f.points` the returns within the
// sensor's range (Sensor::in_range: the vehicle's own returns within min_range_m and those beyond
// max_range_m are not scene geometry for any method); the points the projection drops (and
// NaN/Inf records) are added to `dropped` and logged per frame at debug level. With
// `labels_path` (actor_truth.hpp) the per-point labels are read into `f.labels` and kept with
// their points (IoError when their count is not the scan's). `intensity_scale` multiplies the
// intensities as read (plain folders: plain_scans_intensity_scale).
void load_frame_scan(Frame& f, const std::string& scan_path, const Sensor& s, bool load_points,
                     ProjectionStats& dropped, const std::string& labels_path = "",
                     float intensity_scale = 1.0f);
// Fills timestamps relative to the first frame and the split; logs a summary with the totals
// of dropped points.
void finish_dataset(Dataset& d, const ProjectionStats& dropped);

Dataset load_kitti360(const std::string& root, const LoadOptions& opt, bool synthetic);
Dataset load_kitti_odometry(const std::string& root, const LoadOptions& opt);
Dataset load_nuscenes(const std::string& root, const LoadOptions& opt);
Dataset load_scans(const std::string& path, const LoadOptions& opt);
// The sensor of plain scans: opt.sensor, else the estimate's matching preset, else the
// estimate (sensor_estimate.hpp); opt.rate_hz, when set, is its rate.
Sensor plain_scans_sensor(const std::vector<std::string>& files, const LoadOptions& opt);
// The methods take intensities in [0, 1]. A folder whose sampled scans (read_scan_sample) hold
// intensities above 1 carries 8-bit (max <= 255: scale 1/255, the nuScenes reader's own rule)
// or 16-bit (<= 65535: 1/65535) values; above that, 1/max. One scale per folder, so every scan
// of it is read alike.
float plain_scans_intensity_scale(const std::vector<std::string>& files);

}  // namespace sgnlf::detail
