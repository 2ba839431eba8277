// scan_times (see scan_times.hpp).
#include "datasets/scan_times.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/trajectory_io.hpp"

namespace sgnlf {
namespace fs = std::filesystem;

namespace {

// The file name without the scan extensions (".pcd.bin" counts as one).
std::string scan_stem(const std::string& path) {
  std::string n = fs::path(path).filename().string();
  for (const char* ext : {".pcd.bin", ".bin", ".pcd", ".ply"}) {
    const std::string e(ext);
    if (n.size() > e.size() && n.compare(n.size() - e.size(), e.size(), e) == 0) {
      n.resize(n.size() - e.size());
      break;
    }
  }
  return n;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Digits [b, e) as an integer (at most 19 digits: fits int64).
int64_t digits_value(const std::string& s, size_t b, size_t e) {
  int64_t v = 0;
  for (size_t i = b; i < e; ++i) v = v * 10 + (s[i] - '0');
  return v;
}

}  // namespace

double ScanTimes::rate_hz() const {
  std::vector<double> dt;
  for (size_t i = 1; i < seconds.size(); ++i) dt.push_back(seconds[i] - seconds[i - 1]);
  if (dt.empty()) return 0.0;
  std::nth_element(dt.begin(), dt.begin() + long(dt.size() / 2), dt.end());
  const double m = dt[dt.size() / 2];
  return m > 0.0 ? 1.0 / m : 0.0;
}

std::optional<double> timestamp_from_file_name(const std::string& path) {
  const std::string s = scan_stem(path);
  size_t e = s.size();
  while (e > 0 && !is_digit(s[e - 1])) --e;
  size_t b = e;
  while (b > 0 && is_digit(s[b - 1])) --b;
  if (b == e) return std::nullopt;
  // "S.F": seconds with a fraction (10 digits before the point).
  if (b >= 2 && s[b - 1] == '.' && is_digit(s[b - 2])) {
    size_t sb = b - 1;
    while (sb > 0 && is_digit(s[sb - 1])) --sb;
    if (b - 1 - sb != 10 || e - b > 9) return std::nullopt;
    return double(digits_value(s, sb, b - 1)) + double(digits_value(s, b, e)) * std::pow(10.0, -double(e - b));
  }
  const size_t n = e - b;
  const int64_t v = n <= 19 ? digits_value(s, b, e) : 0;
  switch (n) {
    case 19: return double(v) * 1e-9;
    case 16: return double(v) * 1e-6;  // as the nuScenes loader reads its tables' microseconds
    case 13: return double(v) * 1e-3;
    case 10: return double(v);
    default: return std::nullopt;  // frame numbers ("000042") and the like
  }
}

std::optional<ScanTimes> scan_times(const std::string& dir, const std::vector<std::string>& files) {
  const fs::path times = fs::path(dir) / "times.txt";
  if (fs::is_regular_file(times)) {
    std::ifstream in(times);
    if (!in) throw IoError(times.string() + ": cannot be read");
    ScanTimes t;
    t.source = "times.txt";
    std::string line;
    int k = 0;
    while (std::getline(in, line)) {
      ++k;
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      const auto v = io::parse_numbers(line, times.string(), k);
      if (v.size() != 1 || !std::isfinite(v[0]))
        throw IoError(times.string() + ":" + std::to_string(k) + ": expected one time in seconds per line");
      if (!t.seconds.empty() && !(v[0] > t.seconds.back()))
        throw IoError(times.string() + ":" + std::to_string(k) + ": times must increase (" +
                      std::to_string(v[0]) + " after " + std::to_string(t.seconds.back()) + ")");
      t.seconds.push_back(v[0]);
    }
    if (t.seconds.size() != files.size())
      throw IoError(times.string() + ": " + std::to_string(t.seconds.size()) + " times for " +
                    std::to_string(files.size()) + " scan files in " + dir);
    return t;
  }
  ScanTimes t;
  t.source = "file names";
  for (const auto& f : files) {
    const auto v = timestamp_from_file_name(f);
    if (!v || (!t.seconds.empty() && !(*v > t.seconds.back()))) return std::nullopt;
    t.seconds.push_back(*v);
  }
  if (t.seconds.empty()) return std::nullopt;
  return t;
}

}  // namespace sgnlf
