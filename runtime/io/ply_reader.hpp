// PLY scans: ascii, binary_little_endian and binary_big_endian. The points are the `vertex`
// element's x y z (any property type: char uchar short ushort int uint float double or their
// int8 … float64 names), with intensity (also `reflectance`, `scalar_intensity`, `i`), ring
// and time (also `timestamp`, `t`) kept when present; other vertex properties and every other
// element (faces with list properties, before or after the vertices) are skipped record by
// record, so a truncated or overlong file is still refused. Intensity is kept as stored
// (stats->max_intensity tells its scale). Bad input throws IoError naming the file and the
// header line or byte offset.
#pragma once
#include <string>
#include <vector>

#include "io/scan_io.hpp"

namespace sgnlf::io {

std::vector<PointXYZI> read_ply(const std::string& path, ScanReadStats* stats = nullptr,
                                ScanExtras* extras = nullptr);

}  // namespace sgnlf::io
