#include "io/pcd_reader.hpp"

#include "core/error.hpp"
#include "io/lzf.hpp"
#include "io/pcd_header.hpp"
#include "io/scan_assembler.hpp"

namespace sgnlf::io {
namespace {
using detail::PcdData;
using detail::PcdHeader;

[[noreturn]] void fail_at(const std::string& path, size_t offset, const std::string& what) {
  throw IoError(path + ": byte offset " + std::to_string(offset) + ": " + what);
}

// The field of each role the header has (null: absent).
struct RoleFields {
  const detail::PcdField* field[kFieldRoles] = {};
  explicit RoleFields(const PcdHeader& h) {
    for (size_t r = 0; r < kFieldRoles; ++r)
      if (h.field_of_role[r] >= 0) field[r] = &h.fields[size_t(h.field_of_role[r])];
  }
};

void read_binary(const std::string& path, const PcdHeader& h, const char* bytes, size_t size, ScanAssembler& out) {
  const size_t avail = size - h.data_offset;
  if (h.points > avail / h.record_size)
    fail_at(path, h.data_offset, "truncated: POINTS " + std::to_string(h.points) + " x " + std::to_string(h.record_size) +
                                     " bytes, but only " + std::to_string(avail) + " bytes follow the header");
  const size_t need = size_t(h.points) * h.record_size;
  if (avail != need)
    fail_at(path, h.data_offset + need, std::to_string(avail - need) + " bytes after the last of the POINTS " + std::to_string(h.points));
  const RoleFields rf(h);
  std::array<double, kFieldRoles> v{};
  for (size_t i = 0; i < h.points; ++i) {
    const size_t base = h.data_offset + i * h.record_size;
    for (size_t r = 0; r < kFieldRoles; ++r)
      if (rf.field[r]) v[r] = decode_scalar(bytes + base + rf.field[r]->offset, rf.field[r]->type, false);
    out.add(v, base);
  }
}

uint32_t le32(const char* p) {
  return uint32_t(uint8_t(p[0])) | uint32_t(uint8_t(p[1])) << 8 | uint32_t(uint8_t(p[2])) << 16 | uint32_t(uint8_t(p[3])) << 24;
}

void read_compressed(const std::string& path, const PcdHeader& h, const char* bytes, size_t size, ScanAssembler& out) {
  const size_t at = h.data_offset, avail = size - at;
  if (avail < 8) fail_at(path, at, "truncated: binary_compressed data needs 8 size bytes, " + std::to_string(avail) + " follow the header");
  const uint64_t csize = le32(bytes + at), usize = le32(bytes + at + 4);
  if (h.points > kMaxScanBytes / h.record_size || usize != h.points * h.record_size)
    fail_at(path, at + 4, "uncompressed size " + std::to_string(usize) + " is not POINTS " + std::to_string(h.points) +
                              " x " + std::to_string(h.record_size) + " bytes");
  if (csize > avail - 8)
    fail_at(path, at, "truncated: compressed size " + std::to_string(csize) + " but " + std::to_string(avail - 8) + " bytes follow");
  if (csize < avail - 8)
    fail_at(path, at + 8 + csize, std::to_string(avail - 8 - csize) + " bytes after the compressed data");
  if (usize > csize * kLzfMaxRatio)
    fail_at(path, at, "LZF stream corrupt: " + std::to_string(csize) + " compressed bytes cannot hold " + std::to_string(usize));
  std::vector<uint8_t> raw(usize);
  std::string err;
  size_t off = 0;
  if (!lzf_decompress(reinterpret_cast<const uint8_t*>(bytes + at + 8), csize, raw.data(), raw.size(), err, off))
    fail_at(path, at + 8 + off, "LZF stream corrupt: " + err);
  const RoleFields rf(h);
  std::array<double, kFieldRoles> v{};
  for (size_t i = 0; i < h.points; ++i) {
    for (size_t r = 0; r < kFieldRoles; ++r) {
      const detail::PcdField* f = rf.field[r];
      if (f) v[r] = decode_scalar(reinterpret_cast<const char*>(raw.data()) + h.points * f->offset + i * f->size * f->count, f->type, false);
    }
    out.add(v, at);
  }
}

void read_ascii(const std::string& path, const PcdHeader& h, const char* bytes, size_t size, ScanAssembler& out) {
  LineCursor cur(bytes + h.data_offset, size - h.data_offset);
  std::string_view line;
  size_t n = 0;
  std::array<double, kFieldRoles> v{};
  std::vector<int> role_of_field(h.fields.size(), -1);
  for (size_t r = 0; r < kFieldRoles; ++r)
    if (h.field_of_role[r] >= 0) role_of_field[size_t(h.field_of_role[r])] = int(r);
  while (cur.next(line)) {
    const auto tok = split_ws(line);
    if (tok.empty()) continue;
    const size_t offset = h.data_offset + cur.line_offset(), line_no = h.data_line + cur.line_number();
    auto where = [&] { return "line " + std::to_string(line_no) + " (byte offset " + std::to_string(offset) + ")"; };
    if (n == h.points) throw IoError(path + ": " + where() + ": more points than POINTS " + std::to_string(h.points));
    if (tok.size() != h.values_per_point)
      throw IoError(path + ": " + where() + ": " + std::to_string(tok.size()) + " values, FIELDS and COUNT declare " +
                    std::to_string(h.values_per_point));
    for (size_t k = 0; k < h.fields.size(); ++k) {
      const auto& f = h.fields[k];
      for (size_t c = 0; c < f.count; ++c) {
        double d = 0;
        if (!parse_scalar(tok[f.value_index + c], f.type, d))
          throw IoError(path + ": " + where() + ": '" + std::string(tok[f.value_index + c].substr(0, 40)) +
                        "' is not a value of field '" + f.name + "' (SIZE " + std::to_string(f.size) + ")");
        if (role_of_field[k] >= 0) v[size_t(role_of_field[k])] = d;
      }
    }
    out.add(v, offset);
    ++n;
  }
  if (n != h.points)
    fail_at(path, size, "truncated: " + std::to_string(n) + " of POINTS " + std::to_string(h.points) + " points");
}

}  // namespace

std::vector<PointXYZI> read_pcd(const std::string& path, ScanReadStats* stats, ScanExtras* extras) {
  const auto bytes = read_file_bytes(path, kMaxScanBytes);
  if (bytes.empty()) throw IoError(path + ": empty scan (0 bytes)");
  const PcdHeader h = detail::parse_pcd_header(path, bytes.data(), bytes.size());
  const size_t avail = bytes.size() - h.data_offset;
  // Room for no more points than the data could hold (an ascii value takes two bytes at least).
  const size_t reserve = h.data == PcdData::kAscii ? avail / (2 * h.values_per_point)
                         : h.data == PcdData::kBinary ? avail / h.record_size
                                                       : avail / h.record_size * kLzfMaxRatio;
  ScanAssembler out(path, size_t(h.points), reserve, h.field_of_role, extras);
  if (h.data == PcdData::kAscii) read_ascii(path, h, bytes.data(), bytes.size(), out);
  else if (h.data == PcdData::kBinary) read_binary(path, h, bytes.data(), bytes.size(), out);
  else read_compressed(path, h, bytes.data(), bytes.size(), out);
  return out.finish(stats);
}

}  // namespace sgnlf::io
