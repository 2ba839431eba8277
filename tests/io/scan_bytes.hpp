// Test helpers for the PCD and PLY reader tests: building files byte by byte in a chosen byte
// order, comparing scans bit for bit, and catching the IoError a bad file must raise.
#pragma once
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::test {

struct Bytes {
  std::string s;
  template <typename T>
  Bytes& le(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));  // the test hosts are little-endian (x86-64, aarch64)
    s.append(b, sizeof(T));
    return *this;
  }
  template <typename T>
  Bytes& be(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (size_t k = sizeof(T); k-- > 0;) s += b[k];
    return *this;
  }
  Bytes& str(const std::string& t) {
    s += t;
    return *this;
  }
  void write(const std::string& path) const { io::write_file_bytes(path, s.data(), s.size()); }
};

// The message of the IoError `f` throws; "" when it throws none (another exception escapes).
inline std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

// A scan with a fixed seed: coordinates ±80 m with every float bit random, intensity 0–255,
// rings 0–127 (and a few negative and large ones), times around 1.7e9 s with full precision.
inline std::vector<PointXYZI> random_scan(size_t n, uint64_t seed, io::ScanExtras* ex) {
  Rng rng(seed);
  std::vector<PointXYZI> pts;
  ex->ring.clear();
  ex->time.clear();
  for (size_t i = 0; i < n; ++i) {
    pts.push_back({rng.uniform(-80.f, 80.f), rng.uniform(-80.f, 80.f), rng.uniform(-3.f, 10.f), rng.uniform(0.f, 255.f)});
    ex->ring.push_back(i % 17 == 5 ? -int32_t(i) : i % 13 == 7 ? int32_t(2000000000 + i) : int32_t(rng.below(128)));
    ex->time.push_back(1.7e9 + rng.uniform_double());
  }
  ex->has_ring = ex->has_time = ex->has_intensity = true;
  return pts;
}

inline bool same_bits(const std::vector<PointXYZI>& a, const std::vector<PointXYZI>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(PointXYZI)) == 0);
}

}  // namespace sgnlf::test
