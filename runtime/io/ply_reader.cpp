#include "io/ply_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "core/error.hpp"
#include "io/ply_header.hpp"
#include "io/scan_assembler.hpp"

namespace sgnlf::io {
namespace {
using detail::PlyElement;
using detail::PlyFormat;
using detail::PlyHeader;

// Role of each vertex property (-1: skipped).
std::vector<int> vertex_roles(const PlyHeader& h) {
  std::vector<int> role(h.elements[h.vertex].props.size(), -1);
  for (size_t r = 0; r < kFieldRoles; ++r)
    if (h.field_of_role[r] >= 0) role[size_t(h.field_of_role[r])] = int(r);
  return role;
}

std::string count_str(double n) {  // a decoded count of any integer type (no int cast overflow)
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.0f", n);
  return buf;
}

std::string where(const PlyElement& e, uint64_t record) {
  return "element " + e.name + " record " + std::to_string(record);
}

void read_binary(const std::string& path, const PlyHeader& h, const char* b, size_t size, ScanAssembler& out) {
  const bool be = h.format == PlyFormat::kBinaryBigEndian;
  const auto roles = vertex_roles(h);
  size_t pos = h.data_offset;
  auto fail = [&](size_t at, const std::string& what) -> void {
    throw IoError(path + ": byte offset " + std::to_string(at) + ": " + what);
  };
  for (size_t k = 0; k < h.elements.size(); ++k) {
    const PlyElement& e = h.elements[k];
    const bool is_vertex = k == h.vertex;
    if (!e.has_list && e.record_size > 0 && e.count > (size - pos) / e.record_size)
      fail(pos, "truncated: element " + e.name + " has " + std::to_string(e.count) + " records of " +
                    std::to_string(e.record_size) + " bytes, " + std::to_string(size - pos) + " bytes are left");
    if (!e.has_list && !is_vertex) {  // fixed-size records: skipped at once
      pos += size_t(e.count) * e.record_size;
      continue;
    }
    std::array<double, kFieldRoles> v{};
    for (uint64_t i = 0; i < e.count; ++i) {
      const size_t start = pos;
      for (size_t p = 0; p < e.props.size(); ++p) {
        const auto& pr = e.props[p];
        if (pr.is_list) {
          const size_t cs = scalar_size(pr.count_type);
          if (size - pos < cs) fail(pos, "truncated: " + where(e, i) + ", list " + pr.name + " count cut off");
          const double n = decode_scalar(b + pos, pr.count_type, be);
          pos += cs;
          const size_t is = scalar_size(pr.type);
          if (n < 0 || n > double((size - pos) / is))
            fail(pos - cs, (n < 0 ? "negative list count " : "truncated: list count ") + count_str(n) +
                               " in " + where(e, i) + ", property " + pr.name);
          pos += size_t(n) * is;
          continue;
        }
        const size_t s = scalar_size(pr.type);
        if (size - pos < s) fail(pos, "truncated: " + where(e, i) + ", property " + pr.name + " cut off");
        if (is_vertex && roles[p] >= 0) v[size_t(roles[p])] = decode_scalar(b + pos, pr.type, be);
        pos += s;
      }
      if (is_vertex) out.add(v, start);
    }
  }
  if (pos != size) fail(pos, std::to_string(size - pos) + " bytes after the last element");
}

// Whitespace-separated tokens of the ascii data with their line numbers and byte offsets.
class Tokens {
 public:
  Tokens(const char* b, size_t size, size_t pos, size_t line) : b_(b), size_(size), pos_(pos), line_(line) {}
  bool next(std::string_view& tok) {
    while (pos_ < size_ && std::isspace(static_cast<unsigned char>(b_[pos_]))) {
      if (b_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ == size_) return false;
    start_ = pos_;
    while (pos_ < size_ && !std::isspace(static_cast<unsigned char>(b_[pos_]))) ++pos_;
    tok = std::string_view(b_ + start_, pos_ - start_);
    return true;
  }
  std::string here() const {
    return "line " + std::to_string(line_) + " (byte offset " + std::to_string(start_) + ")";
  }
  size_t start() const { return start_; }
  size_t left() const { return size_ - pos_; }

 private:
  const char* b_;
  size_t size_, pos_, line_, start_ = 0;
};

void read_ascii(const std::string& path, const PlyHeader& h, const char* b, size_t size, ScanAssembler& out) {
  const auto roles = vertex_roles(h);
  Tokens t(b, size, h.data_offset, h.data_line + 1);
  std::string_view tok;
  auto value = [&](const PlyElement& e, uint64_t i, const std::string& prop, ScalarType type) {
    if (!t.next(tok))
      throw IoError(path + ": byte offset " + std::to_string(size) + ": truncated: " + where(e, i) + ", property " + prop +
                    " missing (" + std::to_string(i) + " of " + std::to_string(e.count) + " records read)");
    double d = 0;
    if (!parse_scalar(tok, type, d))
      throw IoError(path + ": " + t.here() + ": '" + std::string(tok.substr(0, 40)) + "' is not a value of " +
                    where(e, i) + ", property " + prop);
    return d;
  };
  for (size_t k = 0; k < h.elements.size(); ++k) {
    const PlyElement& e = h.elements[k];
    const bool is_vertex = k == h.vertex;
    if (e.props.empty()) continue;  // records without a value take no token
    std::array<double, kFieldRoles> v{};
    for (uint64_t i = 0; i < e.count; ++i) {
      size_t start = 0;
      for (size_t p = 0; p < e.props.size(); ++p) {
        const auto& pr = e.props[p];
        const double d = value(e, i, pr.name, pr.is_list ? pr.count_type : pr.type);
        if (p == 0) start = t.start();
        if (pr.is_list) {
          if (d < 0 || d > double(t.left()))
            throw IoError(path + ": " + t.here() + ": list count " + count_str(d) + " in " + where(e, i) +
                          (d < 0 ? " is negative" : " exceeds the bytes left"));
          for (uint64_t c = 0; c < uint64_t(d); ++c) value(e, i, pr.name, pr.type);
        } else if (is_vertex && roles[p] >= 0) {
          v[size_t(roles[p])] = d;
        }
      }
      if (is_vertex) out.add(v, start);
    }
  }
  if (t.next(tok)) throw IoError(path + ": " + t.here() + ": data after the last element");
}

}  // namespace

std::vector<PointXYZI> read_ply(const std::string& path, ScanReadStats* stats, ScanExtras* extras) {
  const auto bytes = read_file_bytes(path, kMaxScanBytes);
  if (bytes.empty()) throw IoError(path + ": empty scan (0 bytes)");
  const PlyHeader h = detail::parse_ply_header(path, bytes.data(), bytes.size());
  const PlyElement& v = h.elements[h.vertex];
  const size_t avail = bytes.size() - h.data_offset;
  // Room for no more points than the data could hold (an ascii value takes two bytes at least).
  size_t min_record = v.props.size() * (h.format == PlyFormat::kAscii ? 2 : 1);
  if (h.format != PlyFormat::kAscii && !v.has_list) min_record = v.record_size;
  ScanAssembler out(path, size_t(v.count), avail / std::max<size_t>(1, min_record), h.field_of_role, extras);
  if (h.format == PlyFormat::kAscii) read_ascii(path, h, bytes.data(), bytes.size(), out);
  else read_binary(path, h, bytes.data(), bytes.size(), out);
  return out.finish(stats);
}

}  // namespace sgnlf::io
