// Point-cloud writers for viewers, other tools, tests and the fuzz seeds: PLY (ascii, binary
// little- or big-endian) and PCD v0.7 (ascii, binary, binary_compressed with LZF), fields
// x y z intensity as float32, then optionally ring (int32: PCD I4, PLY int) and time (float64:
// PCD F8, PLY double). Text values carry every bit (%.9g floats, %.17g doubles), so the
// readers (io/pcd_reader.hpp, io/ply_reader.hpp) give back exactly what was written.
#pragma once
#include <string>
#include <vector>

#include "geometry/range_image.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::io {

enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };
enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

// Binary little-endian PLY / binary PCD of x y z intensity (the byte layout other tools and
// committed files rely on: the same as the overloads below with kBinaryLittleEndian / kBinary
// and no extras).
void write_ply(const std::string& path, const std::vector<PointXYZI>& pts);
void write_pcd(const std::string& path, const std::vector<PointXYZI>& pts);

// `extras`: ring written when extras->has_ring, time when extras->has_time (each vector must
// hold one value per point; sgnlf::Error otherwise). Intensity is always written.
void write_ply(const std::string& path, const std::vector<PointXYZI>& pts, PlyEncoding encoding,
               const ScanExtras* extras = nullptr);
void write_pcd(const std::string& path, const std::vector<PointXYZI>& pts, PcdEncoding encoding,
               const ScanExtras* extras = nullptr);

}  // namespace sgnlf::io
