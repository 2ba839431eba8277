// When each scan of a plain folder was taken. A folder of scans has no clock of its own; the
// times come from, in this order:
//   1. a times.txt beside the scans (KITTI's: one time in seconds per line, one line per scan
//      file in name order; IoError naming the file and line when its count or a value is bad);
//   2. a timestamp in every file name: the last run of digits of the name without its scan
//      extension, read as nanoseconds (19 digits), microseconds (16: nuScenes'
//      "…__LIDAR_TOP__1538984233547259.pcd.bin"), milliseconds (13) or seconds (10, or
//      "1538984233.547259" with a fraction), used only when every name has one and they
//      increase strictly;
//   3. none: the caller falls back to the sensor's rate.
#pragma once
#include <optional>
#include <string>
#include <vector>

namespace sgnlf {

struct ScanTimes {
  std::vector<double> seconds;  // one per file, absolute as found (the loader makes them relative)
  std::string source;           // "times.txt" or "file names"
  // 1 / the median interval between consecutive scans.
  double rate_hz() const;
};

// The timestamp in one file name (rule 2 above), seconds; nullopt when it has none.
std::optional<double> timestamp_from_file_name(const std::string& path);

// `files` sorted by name, all in `dir`. nullopt when neither times.txt nor the names give times.
std::optional<ScanTimes> scan_times(const std::string& dir, const std::vector<std::string>& files);

}  // namespace sgnlf
