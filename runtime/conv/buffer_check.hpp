// Shared by the launchers of the U-Net layers (max pool, upsampling, channel copy, BCE, box
// mask): the byte-size check of a buffer argument, naming the layer and the argument, and the
// global size of their flat launches.
#pragma once
#include <string>

#include "cl/runtime.hpp"
#include "core/error.hpp"

namespace sgnlf::conv {

inline void check_floats(const cl::Buffer& b, size_t floats, const char* layer, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string(layer) + ": buffer '" + what + "' has " + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(floats * sizeof(float)));
}

// Global size of a flat launch over `items` (pixel, channel) work-items, rounded up to the
// work-group size 64; the kernels index with int, so items above 2^31 − 1 are refused.
inline size_t flat_global(size_t items, const char* layer) {
  if (items > size_t(0x7fffffff))
    throw Error(std::string(layer) + ": " + std::to_string(items) +
                " elements exceed the kernels' int indexing (2^31 - 1); use fewer images");
  return cl::round_up(items, 64);
}

}  // namespace sgnlf::conv
