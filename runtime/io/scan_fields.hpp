// Pieces shared by the PCD and PLY scan readers: the scalar types both formats declare, the
// decoding of one binary or text value, the roles of the fields a scan keeps (x y z, intensity,
// ring, time under their usual names) and a line cursor over a header.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace sgnlf::io {

enum class ScalarType : uint8_t { kI8, kU8, kI16, kU16, kI32, kU32, kI64, kU64, kF32, kF64 };

size_t scalar_size(ScalarType t);
bool scalar_is_integer(ScalarType t);
// PCD: TYPE letter (F, I, U) and SIZE; false when the pair is not one of F4 F8 I1..I8 U1..U8.
bool pcd_scalar_type(char type, long size, ScalarType& out);
// PLY: a property type name (char uchar short ushort int uint float double, int8 … float64).
bool ply_scalar_type(std::string_view name, ScalarType& out);

// The value at `p` (scalar_size(t) bytes, little- or big-endian) as a double.
double decode_scalar(const char* p, ScalarType t, bool big_endian);
// A text value of type `t`; false when `token` is not a number of that type (an integer out of
// its range, a fraction in an integer field, an F4 beyond float). nan/inf allowed for floats.
bool parse_scalar(std::string_view token, ScalarType t, double& out);

// What a scan keeps of a field; kNone: skipped.
enum class FieldRole : uint8_t { kX, kY, kZ, kIntensity, kRing, kTime, kNone };
constexpr size_t kFieldRoles = 6;
const char* role_name(FieldRole r);
// Picks each role's field among `names` (case-insensitive): x, y, z; intensity, reflectance,
// scalar_intensity, i; ring; time, timestamp, t (earlier aliases first). -1: absent. On an
// ambiguity (a name twice) returns false with `error` naming it.
bool assign_roles(const std::vector<std::string>& names, std::array<int, kFieldRoles>& field_of_role,
                  std::string& error);

// Header lines of a text header: each line without its "\n" / "\r\n", with its 1-based number
// and the byte offset of its start.
class LineCursor {
 public:
  LineCursor(const char* data, size_t size) : data_(data), size_(size) {}
  bool next(std::string_view& line);  // false at the end of the buffer
  size_t line_number() const { return line_; }
  size_t line_offset() const { return start_; }
  size_t offset() const { return pos_; }  // just past the current line's "\n"

 private:
  const char* data_;
  size_t size_, pos_ = 0, start_ = 0, line_ = 0;
};

// Whitespace-separated tokens of a line.
std::vector<std::string_view> split_ws(std::string_view line);

}  // namespace sgnlf::io
