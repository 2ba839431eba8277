// Shared by the launchers of the U-Net layers (max pool, upsampling, channel copy, BCE, box
// mask): the byte-size check of a buffer argument, naming the layer and the argument.
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

}  // namespace sgnlf::conv
