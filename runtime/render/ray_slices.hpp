// The launch shape of the per-ray render kernels under the device profile's ray_work_items
// (cl/device_profile.hpp): 1 = one work-item per ray (the cpu profile's kernels, cl::launch_1d);
// W > 1 = a slice of W work-items per ray (kernels/render/ray_slice.clh), several rays per
// work-group of the profile's local size rounded down to a multiple of W (so that no slice
// straddles two work-groups), W and that size passed to the kernels as -DRAY_W, -DRAY_WG.
#pragma once
#include <string>

#include "cl/runtime.hpp"
#include "core/error.hpp"

namespace sgnlf::render {

struct RaySlices {
  int w = 1;      // work-items per ray
  int group = 1;  // work-items per work-group, a multiple of w

  explicit RaySlices(const cl::DeviceProfile& p)
      : w(p.ray_work_items), group(p.local_size / p.ray_work_items * p.ray_work_items) {}

  bool sliced() const { return w > 1; }
  std::string defines() const {
    return "-DRAY_W=" + std::to_string(w) + " -DRAY_WG=" + std::to_string(group);
  }
  // One slice per ray, the global size rounded up to whole work-groups (the kernels give the
  // slices beyond n_rays empty runs; they still reach every barrier).
  cl::Event launch(cl::Kernel& k, int n_rays, const char* what) const {
    const size_t items = size_t(n_rays) * size_t(w);
    require(items < (size_t(1) << 31),
            std::string(what) + ": " + std::to_string(n_rays) + " rays x ray_work_items " +
                std::to_string(w) + " work-items exceed 2^31");
    return k.launch({cl::round_up(items, size_t(group))}, {size_t(group)});
  }
};

}  // namespace sgnlf::render
