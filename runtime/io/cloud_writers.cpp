#include "io/cloud_writers.hpp"

#include <cstring>

#include "io/scan_io.hpp"

namespace sgnlf::io {
namespace {

void write_with_header(const std::string& path, const std::string& header,
                       const std::vector<PointXYZI>& pts) {
  std::vector<char> buf(header.size() + pts.size() * sizeof(PointXYZI));
  std::memcpy(buf.data(), header.data(), header.size());
  if (!pts.empty()) std::memcpy(buf.data() + header.size(), pts.data(), pts.size() * sizeof(PointXYZI));
  write_file_bytes(path, buf.data(), buf.size());
}

}  // namespace

void write_ply(const std::string& path, const std::vector<PointXYZI>& pts) {
  const std::string header = "ply\nformat binary_little_endian 1.0\ncomment sgnlf\nelement vertex " +
                             std::to_string(pts.size()) +
                             "\nproperty float x\nproperty float y\nproperty float z\n"
                             "property float intensity\nend_header\n";
  write_with_header(path, header, pts);
}

void write_pcd(const std::string& path, const std::vector<PointXYZI>& pts) {
  const std::string n = std::to_string(pts.size());
  const std::string header =
      "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n"
      "SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " + n +
      "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA binary\n";
  write_with_header(path, header, pts);
}

}  // namespace sgnlf::io
