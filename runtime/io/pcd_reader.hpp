// PCD scans (PCL's Point Cloud Data, v0.7, and v0.6/v0.5 headers): DATA ascii, binary and
// binary_compressed (LZF, io/lzf.hpp, fields stored one after the other). Fields x y z are
// required; intensity (also `reflectance`, `scalar_intensity`, `i`), ring and time (also
// `timestamp`, `t`) are kept when present, in any order and of any TYPE/SIZE (F4 F8, I1–I8,
// U1–U8); every other field, COUNT > 1 included, is skipped. Intensity is kept as stored
// (stats->max_intensity tells its scale). VIEWPOINT is checked, not applied. Bad input throws
// IoError naming the file and the header line or byte offset.
#pragma once
#include <string>
#include <vector>

#include "io/scan_io.hpp"

namespace sgnlf::io {

std::vector<PointXYZI> read_pcd(const std::string& path, ScanReadStats* stats = nullptr,
                                ScanExtras* extras = nullptr);

}  // namespace sgnlf::io
