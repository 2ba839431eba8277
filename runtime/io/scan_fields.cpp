#include "io/scan_fields.hpp"

#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace sgnlf::io {

size_t scalar_size(ScalarType t) {
  switch (t) {
    case ScalarType::kI8: case ScalarType::kU8: return 1;
    case ScalarType::kI16: case ScalarType::kU16: return 2;
    case ScalarType::kI32: case ScalarType::kU32: case ScalarType::kF32: return 4;
    default: return 8;
  }
}

bool scalar_is_integer(ScalarType t) { return t != ScalarType::kF32 && t != ScalarType::kF64; }

bool pcd_scalar_type(char type, long size, ScalarType& out) {
  static const ScalarType kI[] = {ScalarType::kI8, ScalarType::kI16, ScalarType::kI32, ScalarType::kI64};
  static const ScalarType kU[] = {ScalarType::kU8, ScalarType::kU16, ScalarType::kU32, ScalarType::kU64};
  const int k = size == 1 ? 0 : size == 2 ? 1 : size == 4 ? 2 : size == 8 ? 3 : -1;
  if (k < 0) return false;
  if (type == 'F' && k >= 2) out = k == 2 ? ScalarType::kF32 : ScalarType::kF64;
  else if (type == 'I') out = kI[k];
  else if (type == 'U') out = kU[k];
  else return false;
  return true;
}

bool ply_scalar_type(std::string_view n, ScalarType& out) {
  struct Name { const char* a; const char* b; ScalarType t; };
  static const Name kNames[] = {
      {"char", "int8", ScalarType::kI8},     {"uchar", "uint8", ScalarType::kU8},
      {"short", "int16", ScalarType::kI16},  {"ushort", "uint16", ScalarType::kU16},
      {"int", "int32", ScalarType::kI32},    {"uint", "uint32", ScalarType::kU32},
      {"float", "float32", ScalarType::kF32}, {"double", "float64", ScalarType::kF64},
      {"int64", "int64", ScalarType::kI64},  {"uint64", "uint64", ScalarType::kU64}};
  for (const auto& e : kNames)
    if (n == e.a || n == e.b) {
      out = e.t;
      return true;
    }
  return false;
}

double decode_scalar(const char* p, ScalarType t, bool big_endian) {
  const size_t n = scalar_size(t);
  uint64_t u = 0;  // the value's bits, assembled in the file's byte order whatever the host's
  for (size_t k = 0; k < n; ++k) u |= uint64_t(uint8_t(p[big_endian ? n - 1 - k : k])) << (8 * k);
  const unsigned bits = unsigned(8 * n);
  auto sign_extend = [&] { return bits == 64 ? int64_t(u) : int64_t(u << (64 - bits)) >> (64 - bits); };
  switch (t) {
    case ScalarType::kF32: {
      const uint32_t w = uint32_t(u);
      float f;
      std::memcpy(&f, &w, 4);
      return f;
    }
    case ScalarType::kF64: {
      double d;
      std::memcpy(&d, &u, 8);
      return d;
    }
    case ScalarType::kI8: case ScalarType::kI16: case ScalarType::kI32: case ScalarType::kI64:
      return double(sign_extend());
    default:
      return double(u);
  }
}

bool parse_scalar(std::string_view token, ScalarType t, double& out) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* b = token.data();
  const char* e = b + token.size();
  if (!scalar_is_integer(t)) {
    double d = 0;
    auto r = std::from_chars(b, e, d);
    if (r.ptr != e) return false;
    if (r.ec == std::errc::result_out_of_range) {  // underflow to a subnormal or zero: keep it
      const std::string s(token);
      d = std::strtod(s.c_str(), nullptr);
      if (!std::isfinite(d)) return false;
    } else if (r.ec != std::errc()) {
      return false;
    }
    if (t == ScalarType::kF32) {
      float f = 0;
      auto rf = std::from_chars(b, e, f);  // direct decimal → float, no double rounding
      if (rf.ec == std::errc() && rf.ptr == e) d = f;
      else if (std::isfinite(d) && std::fabs(d) > FLT_MAX) return false;
      else d = double(float(d));
    }
    out = d;
    return true;
  }
  const size_t n = scalar_size(t);
  const bool is_signed = t == ScalarType::kI8 || t == ScalarType::kI16 || t == ScalarType::kI32 || t == ScalarType::kI64;
  if (is_signed) {
    int64_t v = 0;
    auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc() || r.ptr != e) return false;
    const int64_t hi = n == 8 ? std::numeric_limits<int64_t>::max() : (int64_t(1) << (8 * n - 1)) - 1;
    if (v > hi || v < -hi - 1) return false;
    out = double(v);
  } else {
    uint64_t v = 0;
    auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc() || r.ptr != e) return false;
    if (n < 8 && v >> (8 * n) != 0) return false;
    out = double(v);
  }
  return true;
}

const char* role_name(FieldRole r) {
  static const char* kNames[] = {"x", "y", "z", "intensity", "ring", "time", "none"};
  return kNames[size_t(r)];
}

bool assign_roles(const std::vector<std::string>& names, std::array<int, kFieldRoles>& field_of_role,
                  std::string& error) {
  static const std::vector<std::vector<std::string>> kAliases = {
      {"x"}, {"y"}, {"z"}, {"intensity", "reflectance", "scalar_intensity", "i"}, {"ring"},
      {"time", "timestamp", "t"}};
  std::vector<std::string> lower(names.size());
  for (size_t k = 0; k < names.size(); ++k)
    for (char c : names[k]) lower[k] += char(std::tolower(static_cast<unsigned char>(c)));
  for (size_t r = 0; r < kFieldRoles; ++r) {
    field_of_role[r] = -1;
    for (const auto& alias : kAliases[r]) {
      for (size_t k = 0; k < lower.size(); ++k) {
        if (lower[k] != alias) continue;
        if (field_of_role[r] >= 0) {
          error = "field '" + alias + "' appears twice (fields " + std::to_string(field_of_role[r]) +
                  " and " + std::to_string(k) + ")";
          return false;
        }
        field_of_role[r] = int(k);
      }
      if (field_of_role[r] >= 0) break;
    }
  }
  return true;
}

bool LineCursor::next(std::string_view& line) {
  if (pos_ >= size_) return false;
  start_ = pos_;
  const void* nl = std::memchr(data_ + pos_, '\n', size_ - pos_);
  const size_t end = nl ? size_t(static_cast<const char*>(nl) - data_) : size_;
  line = std::string_view(data_ + start_, end - start_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  pos_ = nl ? end + 1 : size_;
  ++line_;
  return true;
}

std::vector<std::string_view> split_ws(std::string_view line) {
  std::vector<std::string_view> out;
  size_t k = 0;
  while (k < line.size()) {
    while (k < line.size() && std::isspace(static_cast<unsigned char>(line[k]))) ++k;
    const size_t s = k;
    while (k < line.size() && !std::isspace(static_cast<unsigned char>(line[k]))) ++k;
    if (k > s) out.push_back(line.substr(s, k - s));
  }
  return out;
}

}  // namespace sgnlf::io
