#include "io/scan_io.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/log.hpp"
#include "io/pcd_reader.hpp"
#include "io/ply_reader.hpp"

namespace sgnlf::io {
namespace fs = std::filesystem;

std::vector<char> read_file_bytes(const std::string& path, size_t max_bytes) {
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) throw IoError(path + ": cannot open file");
  const auto size = f.tellg();
  const std::streamoff sz = size;
  if (sz > 0 && uint64_t(sz) > max_bytes)
    throw IoError(path + ": " + std::to_string(sz) + " bytes, more than the " +
                  std::to_string(max_bytes) + " this reader accepts");
  std::vector<char> buf(size_t(sz < 0 ? 0 : sz));
  f.seekg(0);
  if (!buf.empty() && !f.read(buf.data(), std::streamsize(buf.size())))
    throw IoError(path + ": read failed at byte offset " + std::to_string(f.gcount()));
  return buf;
}

void write_file_bytes(const std::string& path, const void* data, size_t bytes) {
  const auto parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw IoError(path + ": cannot open for writing");
    f.write(static_cast<const char*>(data), std::streamsize(bytes));
    if (!f) throw IoError(path + ": write failed");
  }
  fs::rename(tmp, path);
}

namespace {

// Shared reader of float32 records with `fields` values each; x, y, z at 0..2, intensity at 3.
std::vector<PointXYZI> read_records(const std::string& path, int fields, float intensity_scale,
                                    ScanReadStats* stats, std::vector<uint8_t>* rings) {
  const auto bytes = read_file_bytes(path, kMaxScanBytes);
  const size_t rec = size_t(fields) * sizeof(float);
  if (bytes.empty()) throw IoError(path + ": empty scan (0 bytes)");
  if (bytes.size() % rec != 0)
    throw IoError(path + ": size " + std::to_string(bytes.size()) + " bytes is not a multiple of " +
                  std::to_string(rec) + " (float32 x " + std::to_string(fields) +
                  " per point): truncated or misaligned record at byte offset " +
                  std::to_string(bytes.size() - bytes.size() % rec));
  const size_t n = bytes.size() / rec;
  std::vector<PointXYZI> pts;
  pts.reserve(n);
  if (rings) rings->clear();
  ScanReadStats st;
  st.records = n;
  std::vector<float> v(static_cast<size_t>(fields), 0.f);
  for (size_t i = 0; i < n; ++i) {
    std::memcpy(v.data(), bytes.data() + i * rec, rec);
    const PointXYZI p{v[0], v[1], v[2], v[3] * intensity_scale};
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) ||
        !std::isfinite(p.intensity)) {
      if (st.non_finite++ == 0) st.first_non_finite = i;
      continue;
    }
    pts.push_back(p);
    if (pts.size() == 1 || p.intensity > st.max_intensity) st.max_intensity = p.intensity;
    if (rings) rings->push_back(uint8_t(std::lround(std::fmax(0.f, std::fmin(255.f, v[4])))));
  }
  if (st.non_finite > 0)
    log::warn(path, ": dropped ", st.non_finite, " of ", n, " points with NaN/Inf values (first: point ",
              st.first_non_finite, " at byte offset ", st.first_non_finite * rec, ")");
  if (pts.empty()) throw IoError(path + ": empty scan (no finite point among " + std::to_string(n) + ")");
  if (stats) *stats = st;
  return pts;
}

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::vector<PointXYZI> read_kitti_bin(const std::string& path, ScanReadStats* stats) {
  return read_records(path, 4, 1.0f, stats, nullptr);
}

std::vector<PointXYZI> read_nuscenes_bin(const std::string& path, ScanReadStats* stats,
                                         std::vector<uint8_t>* rings) {
  return read_records(path, 5, 1.0f / 255.0f, stats, rings);
}

bool is_scan_file(const std::string& path) {
  return ends_with(path, ".bin") || ends_with(path, ".pcd") || ends_with(path, ".ply");
}

std::vector<PointXYZI> read_scan(const std::string& path, ScanReadStats* stats, ScanExtras* extras) {
  if (ends_with(path, ".pcd")) return read_pcd(path, stats, extras);
  if (ends_with(path, ".ply")) return read_ply(path, stats, extras);
  ScanExtras none;
  ScanExtras& ex = extras ? *extras : none;
  ex = ScanExtras{};
  ex.has_intensity = true;
  if (ends_with(path, ".pcd.bin")) {
    std::vector<uint8_t> rings;
    auto pts = read_nuscenes_bin(path, stats, extras ? &rings : nullptr);
    ex.ring.assign(rings.begin(), rings.end());
    ex.has_ring = true;
    return pts;
  }
  if (ends_with(path, ".bin")) return read_kitti_bin(path, stats);
  throw IoError(path + ": unknown scan format (expected .bin, .pcd.bin, .pcd or .ply)");
}

void write_kitti_bin(const std::string& path, const std::vector<PointXYZI>& pts) {
  static_assert(sizeof(PointXYZI) == 16, "PointXYZI must be four packed floats");
  write_file_bytes(path, pts.data(), pts.size() * sizeof(PointXYZI));
}

}  // namespace sgnlf::io
