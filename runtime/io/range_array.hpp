// Raw array format for range images: NumPy .npy v1.0, float32 little-endian, shape (H, W, 3)
// with channels (range m, intensity, return label). Readable with numpy.load.
#pragma once
#include <string>

#include "geometry/range_image.hpp"

namespace sgnlf::io {

void write_range_npy(const std::string& path, const RangeImage& img);
// Reads what write_range_npy writes; anything else throws IoError naming the file.
RangeImage read_range_npy(const std::string& path);

}  // namespace sgnlf::io
