// The header of a PCD file (PCL's Point Cloud Data, v0.7; v0.6 and v0.5 headers read too: no
// VERSION needed, HEIGHT and POINTS default from WIDTH): the key lines VERSION, FIELDS, SIZE,
// TYPE, COUNT, WIDTH, HEIGHT, VIEWPOINT, POINTS and DATA (the last one), `#` comments. Every
// inconsistency (counts that differ, a SIZE that does not fit its TYPE, POINTS ≠ WIDTH·HEIGHT,
// no x/y/z field, an unknown key) throws IoError naming the file, the header line and its
// byte offset. Internal to the PCD reader.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/scan_fields.hpp"

namespace sgnlf::io::detail {

struct PcdField {
  std::string name;
  ScalarType type = ScalarType::kF32;
  size_t size = 4, count = 1;
  size_t offset = 0;       // bytes into a binary record (and × POINTS: the field's block when compressed)
  size_t value_index = 0;  // position of its first value on an ascii line
};

enum class PcdData { kAscii, kBinary, kBinaryCompressed };

struct PcdHeader {
  std::vector<PcdField> fields;
  std::array<int, kFieldRoles> field_of_role{};  // index into fields, -1: absent
  uint64_t width = 0, height = 1, points = 0;
  size_t record_size = 0;   // sum of size × count
  size_t values_per_point = 0;  // sum of count
  PcdData data = PcdData::kBinary;
  size_t data_offset = 0;   // first byte after the DATA line
  size_t data_line = 0;     // its line number (ascii data lines count on from it)
};

PcdHeader parse_pcd_header(const std::string& path, const char* bytes, size_t size);

}  // namespace sgnlf::io::detail
