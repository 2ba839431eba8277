// The launch shape of the element-wise kernels: 1-D (or 1-D × rows), the work-group size from
// the Runtime's device profile (DeviceProfile::local_size; 64 in the built-in profiles), the
// global size rounded up to it; the kernels guard their bounds. Kernels that need a fixed
// work-group size (local-memory reductions, tiled GEMMs) set their shapes themselves.
#pragma once
#include "cl/memory.hpp"
#include "cl/runtime.hpp"
#include "core/error.hpp"

namespace sgnlf::cl {

// The element-wise work-group size of the kernel's Runtime.
inline size_t element_local_size(const Kernel& k) {
  if (!k.runtime()) throw Error("cl::launch_1d: kernel '" + k.name() + "' has no runtime");
  return size_t(k.runtime()->device_profile().local_size);
}

// One work-item per element i < n. trace_elements: as Kernel::launch's (0 = not given).
inline Event launch_1d(Kernel& k, size_t n, size_t trace_elements = 0) {
  const size_t ls = element_local_size(k);
  return k.launch({round_up(n, ls)}, {ls}, trace_elements);
}

// One work-item per (element i < n, row r < rows); rows are whole work-group columns.
inline Event launch_rows(Kernel& k, size_t n, size_t rows, size_t trace_elements = 0) {
  const size_t ls = element_local_size(k);
  return k.launch({round_up(n, ls), rows}, {ls, 1}, trace_elements);
}

}  // namespace sgnlf::cl
