// The device profiles the per-ray slice kernels are tested under (test_volume_slices.cpp,
// test_ray_slices.cpp): the cpu profile with `w` work-items per ray (ray_work_items) in
// work-groups of `local` (w = 1: the cpu kernels).
#pragma once
#include <utility>
#include <vector>

#include "cl/device_profile.hpp"

namespace sgnlf::test {

inline cl::DeviceProfile slice_profile(int w, int local = 64) {
  cl::DeviceProfile p = cl::cpu_profile();
  p.name = "slices";
  p.ray_work_items = w;
  p.local_size = local;
  p.validate();
  return p;
}

// Slice widths and work-groups: 2, 8, the gpu profile's 32, a slice as wide as the group, and
// 16 in groups of 48 (three rays a group); first 1, the cpu kernels, held to the same bounds.
inline const std::vector<std::pair<int, int>> kSliceShapes = {{1, 64},  {2, 64},  {8, 64},
                                                              {32, 64}, {64, 64}, {16, 48}};

}  // namespace sgnlf::test
