// Trajectory and calibration text files: KITTI (12 numbers per line, row-major 3×4), KITTI-360
// `poses.txt` (frame id + 12 numbers), TUM (timestamp tx ty tz qx qy qz qw), and `key: numbers`
// calibration files (KITTI calib.txt, KITTI-360 calib_cam_to_pose.txt). Wrong field or row
// counts throw IoError naming the file and line.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "geometry/se3.hpp"

namespace sgnlf::io {

// One pose per non-empty line, exactly 12 numbers each.
std::vector<Pose> read_kitti_poses(const std::string& path);
void write_kitti_poses(const std::string& path, const std::vector<Pose>& poses);

// KITTI-360 poses.txt: frame id followed by 12 numbers; ids strictly increasing.
std::map<int, Pose> read_indexed_poses(const std::string& path);
void write_indexed_poses(const std::string& path, const std::vector<int>& ids,
                         const std::vector<Pose>& poses);

// TUM: "timestamp tx ty tz qx qy qz qw" per line, '#' comments allowed.
void write_tum_poses(const std::string& path, const std::vector<double>& timestamps,
                     const std::vector<Pose>& poses);
std::vector<std::pair<double, Pose>> read_tum_poses(const std::string& path);

// "key: v1 v2 ..." lines (also a bare line of numbers, stored under key ""). Keys keep order.
std::map<std::string, std::vector<double>> read_key_values(const std::string& path);
// The 3×4 pose stored under `key`; IoError naming the file when absent or not 12 numbers.
Pose key_pose(const std::map<std::string, std::vector<double>>& kv, const std::string& key,
              const std::string& path);

// Parses whitespace-separated numbers of one line; IoError "path:line: ..." on a bad token.
std::vector<double> parse_numbers(const std::string& text, const std::string& path, int line);

}  // namespace sgnlf::io
