#include "io/cloud_writers.hpp"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "core/error.hpp"
#include "io/lzf.hpp"

namespace sgnlf::io {
namespace {

// One written field: its names and types in both formats and its value per point.
enum class Kind { kFloat, kInt, kDouble };
struct Column {
  const char* name;
  Kind kind;
  size_t size() const { return kind == Kind::kDouble ? 8 : 4; }
  const char* pcd_type() const { return kind == Kind::kInt ? "I" : "F"; }
  const char* ply_type() const { return kind == Kind::kFloat ? "float" : kind == Kind::kInt ? "int" : "double"; }
};

struct Cloud {
  const std::vector<PointXYZI>& pts;
  const ScanExtras* ex;
  std::vector<Column> cols;

  Cloud(const std::string& path, const std::vector<PointXYZI>& p, const ScanExtras* e) : pts(p), ex(e) {
    cols = {{"x", Kind::kFloat}, {"y", Kind::kFloat}, {"z", Kind::kFloat}, {"intensity", Kind::kFloat}};
    if (ex && ex->has_ring) {
      require(ex->ring.size() == pts.size(), path + ": " + std::to_string(ex->ring.size()) + " rings for " + std::to_string(pts.size()) + " points");
      cols.push_back({"ring", Kind::kInt});
    }
    if (ex && ex->has_time) {
      require(ex->time.size() == pts.size(), path + ": " + std::to_string(ex->time.size()) + " times for " + std::to_string(pts.size()) + " points");
      cols.push_back({"time", Kind::kDouble});
    }
  }
  // The bits of column c of point i (float and int32 in the low 32 bits).
  uint64_t bits(size_t c, size_t i) const {
    const PointXYZI& p = pts[i];
    const float f[4] = {p.x, p.y, p.z, p.intensity};
    uint64_t u = 0;
    if (c < 4) {
      uint32_t w;
      std::memcpy(&w, &f[c], 4);
      u = w;
    } else if (cols[c].kind == Kind::kInt) {
      u = uint32_t(ex->ring[i]);
    } else {
      std::memcpy(&u, &ex->time[i], 8);
    }
    return u;
  }
  void put(std::string& out, size_t c, size_t i, bool big_endian) const {
    const uint64_t u = bits(c, i);
    const size_t n = cols[c].size();
    for (size_t k = 0; k < n; ++k) out += char(u >> (8 * (big_endian ? n - 1 - k : k)));
  }
  void put_text(std::string& out, size_t c, size_t i) const {
    char b[40];
    const PointXYZI& p = pts[i];
    const float f[4] = {p.x, p.y, p.z, p.intensity};
    if (c < 4) std::snprintf(b, sizeof b, "%.9g", double(f[c]));
    else if (cols[c].kind == Kind::kInt) std::snprintf(b, sizeof b, "%d", int(ex->ring[i]));
    else std::snprintf(b, sizeof b, "%.17g", ex->time[i]);
    out += b;
  }
  std::string row_text(size_t i) const {
    std::string s;
    for (size_t c = 0; c < cols.size(); ++c) {
      if (c) s += ' ';
      put_text(s, c, i);
    }
    return s + '\n';
  }
};

void put_le32(std::string& out, uint64_t v) {
  for (int k = 0; k < 4; ++k) out += char(v >> (8 * k));
}

}  // namespace

void write_ply(const std::string& path, const std::vector<PointXYZI>& pts, PlyEncoding enc, const ScanExtras* ex) {
  const Cloud c(path, pts, ex);
  const char* fmt = enc == PlyEncoding::kAscii ? "ascii" : enc == PlyEncoding::kBinaryLittleEndian ? "binary_little_endian" : "binary_big_endian";
  std::string out = std::string("ply\nformat ") + fmt + " 1.0\ncomment sgnlf\nelement vertex " + std::to_string(pts.size()) + "\n";
  for (const auto& col : c.cols) out += std::string("property ") + col.ply_type() + " " + col.name + "\n";
  out += "end_header\n";
  for (size_t i = 0; i < pts.size(); ++i) {
    if (enc == PlyEncoding::kAscii) out += c.row_text(i);
    else
      for (size_t k = 0; k < c.cols.size(); ++k) c.put(out, k, i, enc == PlyEncoding::kBinaryBigEndian);
  }
  write_file_bytes(path, out.data(), out.size());
}

void write_pcd(const std::string& path, const std::vector<PointXYZI>& pts, PcdEncoding enc, const ScanExtras* ex) {
  const Cloud c(path, pts, ex);
  std::string fields, sizes, types, counts;
  for (const auto& col : c.cols) {
    fields += std::string(" ") + col.name;
    sizes += " " + std::to_string(col.size());
    types += std::string(" ") + col.pcd_type();
    counts += " 1";
  }
  const std::string n = std::to_string(pts.size());
  const char* data = enc == PcdEncoding::kAscii ? "ascii" : enc == PcdEncoding::kBinary ? "binary" : "binary_compressed";
  std::string out = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS" + fields + "\nSIZE" + sizes +
                    "\nTYPE" + types + "\nCOUNT" + counts + "\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
                    n + "\nDATA " + data + "\n";
  if (enc == PcdEncoding::kAscii) {
    for (size_t i = 0; i < pts.size(); ++i) out += c.row_text(i);
  } else if (enc == PcdEncoding::kBinary) {
    for (size_t i = 0; i < pts.size(); ++i)
      for (size_t k = 0; k < c.cols.size(); ++k) c.put(out, k, i, false);
  } else {  // field-major ("structure of arrays"), as PCL lays binary_compressed out
    std::string raw;
    for (size_t k = 0; k < c.cols.size(); ++k)
      for (size_t i = 0; i < pts.size(); ++i) c.put(raw, k, i, false);
    const auto z = lzf_compress(reinterpret_cast<const uint8_t*>(raw.data()), raw.size());
    if (raw.size() > UINT32_MAX || z.size() > UINT32_MAX) throw IoError(path + ": too large for binary_compressed (4 GiB)");
    put_le32(out, z.size());
    put_le32(out, raw.size());
    out.append(reinterpret_cast<const char*>(z.data()), z.size());
  }
  write_file_bytes(path, out.data(), out.size());
}

void write_ply(const std::string& path, const std::vector<PointXYZI>& pts) {
  write_ply(path, pts, PlyEncoding::kBinaryLittleEndian);
}

void write_pcd(const std::string& path, const std::vector<PointXYZI>& pts) {
  write_pcd(path, pts, PcdEncoding::kBinary);
}

}  // namespace sgnlf::io
