// Device profiles for the local-tile GEMM tests (MLP and convolutions): the gpu profile with
// the 4 x 4 register block forced on every launch (block 4) or the 1 x 1 one (block 0), and the
// gpu profile with the cpu profile's tiles (gemm = cpu_tiles) to compare against.
#pragma once
#include "cl/device_profile.hpp"

namespace sgnlf::test {

inline cl::DeviceProfile tiles_profile(int block) {
  cl::DeviceProfile p = cl::gpu_profile();
  p.gemm_min_work_items = block == 0 ? (1 << 30) : 0;
  return p;
}

inline cl::DeviceProfile cpu_tiles_profile() {
  cl::DeviceProfile p = cl::gpu_profile();
  p.gemm = cl::GemmVariant::CpuTiles;
  return p;
}

}  // namespace sgnlf::test
