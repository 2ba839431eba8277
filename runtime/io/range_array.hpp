// Raw array format for range images: NumPy .npy v1.0, float32 little-endian, shape (H, W, 3)
// with channels (range m, intensity, return label). Readable with numpy.load.
#pragma once
#include <string>
#include <vector>

#include "geometry/range_image.hpp"

namespace sgnlf::io {

void write_range_npy(const std::string& path, const RangeImage& img);
// One float per pixel (a view's opacity Σw, row-major h × w): shape (H, W), float32. Throws
// sgnlf::Error when `values` does not hold h × w floats.
void write_float_npy(const std::string& path, int h, int w, const std::vector<float>& values);
// Reads what write_range_npy writes; anything else throws IoError naming the file.
RangeImage read_range_npy(const std::string& path);

}  // namespace sgnlf::io
