#include "io/range_array.hpp"

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/error.hpp"
#include "io/scan_io.hpp"

namespace sgnlf::io {

namespace {

// An .npy v1.0 buffer of float32 with `shape` (e.g. "2, 3"), the header written and `n_floats`
// floats of room after it; returns the offset of the data.
size_t npy_buffer(std::vector<char>& buf, const std::string& shape, size_t n_floats) {
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + shape + "), }";
  // Pad so that magic (6) + version (2) + length (2) + dict + '\n' is a multiple of 64.
  while ((10 + dict.size() + 1) % 64 != 0) dict += ' ';
  dict += '\n';
  buf.assign(10 + dict.size() + n_floats * sizeof(float), 0);
  std::memcpy(buf.data(), "\x93NUMPY\x01\x00", 8);
  buf[8] = char(dict.size() & 0xff);
  buf[9] = char(dict.size() >> 8);
  std::memcpy(buf.data() + 10, dict.data(), dict.size());
  return 10 + dict.size();
}

}  // namespace

void write_range_npy(const std::string& path, const RangeImage& img) {
  std::vector<char> buf;
  const size_t at = npy_buffer(
      buf, std::to_string(img.height) + ", " + std::to_string(img.width) + ", 3", img.size() * 3);
  char* out = buf.data() + at;
  for (size_t i = 0; i < img.size(); ++i) {
    const float v[3] = {img.range[i], img.intensity[i], img.ray_drop[i]};
    std::memcpy(out + 12 * i, v, sizeof(v));
  }
  write_file_bytes(path, buf.data(), buf.size());
}

void write_float_npy(const std::string& path, int h, int w, const std::vector<float>& values) {
  if (h <= 0 || w <= 0 || values.size() != size_t(h) * size_t(w))
    throw Error(path + ": " + std::to_string(values.size()) + " values for an image of " +
                std::to_string(h) + " x " + std::to_string(w));
  std::vector<char> buf;
  const size_t at = npy_buffer(buf, std::to_string(h) + ", " + std::to_string(w), values.size());
  std::memcpy(buf.data() + at, values.data(), values.size() * sizeof(float));
  write_file_bytes(path, buf.data(), buf.size());
}

RangeImage read_range_npy(const std::string& path) {
  const auto b = read_file_bytes(path);
  if (b.size() < 10 || std::memcmp(b.data(), "\x93NUMPY\x01\x00", 8) != 0)
    throw IoError(path + ": not a NumPy v1.0 .npy file (bad magic at byte offset 0)");
  const size_t hlen = size_t(uint8_t(b[8])) | (size_t(uint8_t(b[9])) << 8);
  if (10 + hlen > b.size()) throw IoError(path + ": header runs past the end of the file");
  const std::string dict(b.data() + 10, hlen);
  if (dict.find("'<f4'") == std::string::npos || dict.find("False") == std::string::npos)
    throw IoError(path + ": expected float32 little-endian C-order array, header " + dict);
  // The shape is checked against the file size before anything is allocated: a header that
  // claims (2147483647, 2147483647, 3) must not ask for exabytes.
  long long dims[3] = {0, 0, 0};
  const auto pos = dict.find("'shape': (");
  bool ok = pos != std::string::npos;
  const char* q = ok ? dict.c_str() + pos + 10 : nullptr;
  for (int k = 0; ok && k < 3; ++k) {
    char* end = nullptr;
    errno = 0;
    dims[k] = std::strtoll(q, &end, 10);
    ok = end != q && errno == 0 && dims[k] > 0 && dims[k] <= (1LL << 24);
    q = end;
    if (ok && k < 2) {
      while (*q == ' ') ++q;
      ok = *q == ',';
      ++q;
    }
  }
  if (!ok || dims[2] != 3)
    throw IoError(path + ": expected shape (H, W, 3), header " + dict);
  const size_t h = size_t(dims[0]), w = size_t(dims[1]);
  const size_t need = 10 + hlen + h * w * 3 * sizeof(float);
  if (b.size() != need || h * w > size_t(INT32_MAX))
    throw IoError(path + ": size " + std::to_string(b.size()) + " bytes, expected " +
                  std::to_string(need) + " for shape (" + std::to_string(h) + ", " +
                  std::to_string(w) + ", 3)");
  RangeImage img(static_cast<int>(h), static_cast<int>(w));
  const char* p = b.data() + 10 + hlen;
  for (size_t i = 0; i < img.size(); ++i) {
    float v[3];
    std::memcpy(v, p + 12 * i, 12);
    img.range[i] = v[0];
    img.intensity[i] = v[1];
    img.ray_drop[i] = v[2];
  }
  return img;
}

}  // namespace sgnlf::io
