// The header of a PLY file: the `ply` magic line, `format ascii|binary_little_endian|
// binary_big_endian 1.0`, `comment` / `obj_info` lines, `element NAME COUNT` each followed by
// its `property TYPE NAME` and `property list COUNT_TYPE ITEM_TYPE NAME` lines, and
// `end_header`. The scan is the `vertex` element (x y z required; intensity, ring, time kept
// under their usual names); every other element, before or after it, is skipped. Mistakes
// throw IoError naming the file, the header line and its byte offset. Internal to the PLY reader.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/scan_fields.hpp"

namespace sgnlf::io::detail {

struct PlyProperty {
  std::string name;
  ScalarType type = ScalarType::kF32;        // the item type of a list
  bool is_list = false;
  ScalarType count_type = ScalarType::kU8;   // lists only (an integer type)
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> props;
  bool has_list = false;
  size_t record_size = 0;  // bytes of one binary record when it has no list
  size_t line = 0, line_offset = 0;  // its `element` line: number and byte offset
};

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  size_t vertex = 0;  // index of the vertex element
  std::array<int, kFieldRoles> field_of_role{};  // vertex property per role, -1: absent
  size_t data_offset = 0;  // first byte after the end_header line
  size_t data_line = 0;    // that line's number
};

PlyHeader parse_ply_header(const std::string& path, const char* bytes, size_t size);

}  // namespace sgnlf::io::detail
