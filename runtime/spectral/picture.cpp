// Diverging colormap, tiling and libpng output (picture.hpp).
#include "spectral/picture.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace sgnlf::spectral {
namespace {

// t ∈ [−1, 1] → blue (−1), white (0), red (+1).
void diverging(double t, unsigned char* c) {
  t = std::clamp(t, -1.0, 1.0);
  const double lo[3] = {0.23, 0.30, 0.75}, hi[3] = {0.71, 0.02, 0.15};
  for (int i = 0; i < 3; ++i) {
    const double end = t < 0 ? lo[i] : hi[i];
    c[i] = (unsigned char)std::lround(255.0 * (1.0 + (end - 1.0) * std::fabs(t)));
  }
}

}  // namespace

Image tile_maps(const std::vector<float>& values, int n_funcs, int tile_w, int tile_h, int cols) {
  require(values.size() == size_t(n_funcs) * tile_w * tile_h && cols > 0, "tile_maps: bad sizes");
  const int gap = 4, rows = (n_funcs + cols - 1) / cols;
  Image img;
  img.width = cols * tile_w + (cols + 1) * gap;
  img.height = rows * tile_h + (rows + 1) * gap;
  img.rgb.assign(size_t(img.width) * img.height * 3, 255);
  for (int f = 0; f < n_funcs; ++f) {
    const float* v = values.data() + size_t(f) * tile_w * tile_h;
    double vmax = 1e-30;
    for (int i = 0; i < tile_w * tile_h; ++i) vmax = std::max(vmax, double(std::fabs(v[i])));
    const int x0 = gap + (f % cols) * (tile_w + gap), y0 = gap + (f / cols) * (tile_h + gap);
    for (int y = 0; y < tile_h; ++y)
      for (int x = 0; x < tile_w; ++x)
        diverging(v[y * tile_w + x] / vmax, &img.rgb[(size_t(y0 + y) * img.width + x0 + x) * 3]);
  }
  return img;
}

void write_png(const std::string& path, const Image& img) {
  FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) throw IoError("write_png: cannot open '" + path + "'");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(fp);
    throw IoError("write_png: libpng failed writing '" + path + "'");
  }
  png_init_io(png, fp);
  png_set_IHDR(png, info, png_uint_32(img.width), png_uint_32(img.height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < img.height; ++y)
    png_write_row(png, const_cast<png_bytep>(&img.rgb[size_t(y) * img.width * 3]));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(fp);
}

}  // namespace sgnlf::spectral
