#include "io/png_writer.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.hpp"

namespace sgnlf::io {

void write_png(const std::string& path, const RgbImage& img) {
  if (img.height <= 0 || img.width <= 0 || img.rgb.size() != size_t(img.height) * img.width * 3)
    throw IoError(path + ": invalid image of " + std::to_string(img.height) + "x" +
                  std::to_string(img.width));
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw IoError(path + ": cannot open for writing");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    throw IoError(path + ": libpng failed while writing");
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, png_uint_32(img.width), png_uint_32(img.height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int r = 0; r < img.height; ++r)
    png_write_row(png, const_cast<png_bytep>(img.rgb.data() + size_t(r) * img.width * 3));
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0) throw IoError(path + ": close failed");
}

std::array<uint8_t, 3> turbo(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const double t2 = t * t, t3 = t2 * t, t4 = t3 * t, t5 = t4 * t;
  const double r = 0.13572138 + 4.61539260 * t - 42.66032258 * t2 + 132.13108234 * t3 -
                   152.94239396 * t4 + 59.28637943 * t5;
  const double g = 0.09140261 + 2.19418839 * t + 4.84296658 * t2 - 14.18503333 * t3 +
                   4.27729857 * t4 + 2.82956604 * t5;
  const double b = 0.10667330 + 12.64194608 * t - 60.58204836 * t2 + 110.36276771 * t3 -
                   89.90310912 * t4 + 27.34824973 * t5;
  auto q = [](double v) { return uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return {q(r), q(g), q(b)};
}

std::array<uint8_t, 3> depth_colour(double range_m, const RangePictureOptions& opt) {
  return turbo(opt.log_depth ? std::log1p(range_m) / std::log1p(opt.max_range_m)
                             : range_m / opt.max_range_m);
}

RgbImage range_image_picture(const RangeImage& img, const RangePictureOptions& opt) {
  const int rep = std::max(1, opt.row_repeat);
  const int panel = img.height * rep;
  RgbImage out;
  out.width = img.width;
  out.height = 3 * panel + 2 * opt.gap;
  out.rgb.assign(size_t(out.height) * out.width * 3, 0);
  auto put = [&](int y, int x, std::array<uint8_t, 3> c) {
    uint8_t* p = &out.rgb[(size_t(y) * out.width + x) * 3];
    p[0] = c[0];
    p[1] = c[1];
    p[2] = c[2];
  };
  for (int r = 0; r < img.height; ++r)
    for (int c = 0; c < img.width; ++c) {
      const size_t i = img.idx(r, c);
      const bool ret = img.range[i] > 0.f;
      const auto depth = ret ? depth_colour(double(img.range[i]), opt) : std::array<uint8_t, 3>{0, 0, 0};
      const uint8_t g = uint8_t(std::lround(std::clamp(double(img.intensity[i]), 0.0, 1.0) * 255.0));
      const uint8_t m = img.ray_drop[i] > 0.5f ? 255 : 0;
      for (int k = 0; k < rep; ++k) {
        put(r * rep + k, c, depth);
        put(panel + opt.gap + r * rep + k, c, {g, g, g});
        put(2 * (panel + opt.gap) + r * rep + k, c, {m, m, m});
      }
    }
  return out;
}

}  // namespace sgnlf::io
