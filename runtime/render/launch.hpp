// Small helpers shared by the render launchers: buffer size checks and the element-wise launch
// shape (cl::launch_1d: 1-D, the device profile's work-group size, global rounded up; kernels
// guard their bounds).
#pragma once
#include <string>

#include "cl/launch.hpp"
#include "cl/runtime.hpp"
#include "core/error.hpp"

namespace sgnlf::render {

// Throws naming the launcher and argument when `b` holds fewer than `floats` floats.
inline void check_floats(const cl::Buffer& b, size_t floats, const std::string& what) {
  if (!b || b.bytes() < floats * sizeof(float))
    throw Error(what + ": buffer has " + std::to_string(b ? b.bytes() / sizeof(float) : 0) +
                " floats, needs " + std::to_string(floats));
}

using cl::launch_1d;

}  // namespace sgnlf::render
