// LiDAR scan files: KITTI / KITTI-360 `.bin` (float32 × 4: x, y, z, reflectance), nuScenes
// `.pcd.bin` (float32 × 5: x, y, z, intensity 0–255, ring), and users' own `.pcd` / `.ply`
// scans (io/pcd_reader.hpp, io/ply_reader.hpp). Bad files (empty, truncated, misaligned) throw
// IoError naming the file and byte offset; NaN/Inf points are dropped and counted (protocol §2
// formats).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/range_image.hpp"

namespace sgnlf::io {

struct ScanReadStats {
  size_t records = 0;     // records in the file
  size_t non_finite = 0;  // records dropped because a coordinate or intensity was NaN/Inf
  size_t first_non_finite = 0;  // index of the first of them (valid when non_finite > 0)
  // Largest intensity among the kept points (0 when the file has none). The PCD and PLY readers
  // keep intensity as stored: a value above 1 means a 0–255 (or other) scale the caller chooses
  // how to map.
  float max_intensity = 0.f;
};

// Per-point values beyond x y z intensity, in step with the returned (finite) points. Filled
// by the readers that know them: ring from nuScenes, PCD and PLY; time from PCD and PLY.
struct ScanExtras {
  std::vector<int32_t> ring;  // laser (beam) index
  std::vector<double> time;   // as stored (seconds or the file's unit; not normalised)
  bool has_intensity = false, has_ring = false, has_time = false;
};

// KITTI .bin: reflectance kept as is (already in [0, 1]).
std::vector<PointXYZI> read_kitti_bin(const std::string& path, ScanReadStats* stats = nullptr);
// nuScenes .pcd.bin: intensity divided by 255; `rings` (optional) receives the ring index.
std::vector<PointXYZI> read_nuscenes_bin(const std::string& path, ScanReadStats* stats = nullptr,
                                         std::vector<uint8_t>* rings = nullptr);
// Picks the reader by file name (".pcd.bin" → nuScenes, ".bin" → KITTI, ".pcd" → read_pcd,
// ".ply" → read_ply). `extras` (optional) receives what the format has beyond x y z intensity.
std::vector<PointXYZI> read_scan(const std::string& path, ScanReadStats* stats = nullptr,
                                 ScanExtras* extras = nullptr);
// True for the names read_scan reads: .bin (and .pcd.bin), .pcd, .ply.
bool is_scan_file(const std::string& path);

void write_kitti_bin(const std::string& path, const std::vector<PointXYZI>& pts);

// Whole-file binary read; throws IoError naming the file (also when it holds more than
// `max_bytes`, checked before reading).
std::vector<char> read_file_bytes(const std::string& path, size_t max_bytes = SIZE_MAX);
// Largest scan file read_scan accepts: a real one is 1–3 MB (120 k points × 16–20 bytes).
constexpr size_t kMaxScanBytes = size_t(1) << 30;
// Writes bytes atomically (temporary file + rename).
void write_file_bytes(const std::string& path, const void* data, size_t bytes);

}  // namespace sgnlf::io
