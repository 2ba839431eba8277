// Small helpers shared by the render launchers: buffer size checks and the fixed launch shape
// (1-D, local size 64, global rounded up; kernels guard their bounds).
#pragma once
#include <string>

#include "cl/runtime.hpp"
#include "core/error.hpp"

namespace sgnlf::render {

inline constexpr size_t kLocalSize = 64;

// Throws naming the launcher and argument when `b` holds fewer than `floats` floats.
inline void check_floats(const cl::Buffer& b, size_t floats, const std::string& what) {
  if (!b || b.bytes() < floats * sizeof(float))
    throw Error(what + ": buffer has " + std::to_string(b ? b.bytes() / sizeof(float) : 0) +
                " floats, needs " + std::to_string(floats));
}

inline cl::Event launch_1d(cl::Kernel& k, size_t n) {
  return k.launch({cl::round_up(n, kLocalSize)}, {kLocalSize});
}

}  // namespace sgnlf::render
