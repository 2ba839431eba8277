// Point-cloud writers for viewers and other tools: binary little-endian PLY (x y z intensity as
// float32) and PCD v0.7 (binary, fields x y z intensity).
#pragma once
#include <string>
#include <vector>

#include "geometry/range_image.hpp"

namespace sgnlf::io {

void write_ply(const std::string& path, const std::vector<PointXYZI>& pts);
void write_pcd(const std::string& path, const std::vector<PointXYZI>& pts);

}  // namespace sgnlf::io
