// HeadBand: launches kernels/pipeline/head_band.cl.
#include "pipeline/model/head_band.hpp"

#include <cstdint>
#include <vector>

#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

HeadBand::HeadBand(cl::Runtime& rt, int max_rays, int max_samples, float threshold)
    : thr_(threshold),
      band_k_(rt.kernel("pipeline/head_band.cl", "pipeline_head_band")),
      gather_(rt.kernel("pipeline/head_band.cl", "pipeline_band_gather")),
      scatter_(rt.kernel("pipeline/head_band.cl", "pipeline_band_scatter_live")),
      expand_(rt.kernel("pipeline/head_band.cl", "pipeline_band_expand_head")) {
  const size_t R = size_t(max_rays), N = R * size_t(max_samples);
  begin_ = floats(rt, R), count_ = floats(rt, R), offset_ = floats(rt, R + 1);
  row_ray_ = floats(rt, N), dens_b_ = floats(rt, N * kDensStride);
  head_b_ = floats(rt, N * 2), g_head_b_ = floats(rt, N * 2);
  g_dens_b_ = floats(rt, N * kDensStride);
}

long HeadBand::select(int n_rays, int M, SampleCompaction& live, const cl::Buffer& w,
                      const cl::Buffer& dens) {
  const size_t global = cl::round_up(size_t(n_rays) * size_t(M), 64);
  band_k_.set_args(n_rays, M, thr_, live.offsets(), w, begin_, count_);
  band_k_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
  // The step's second host sync: the band's size sets the head's row count.
  const std::vector<int32_t> count = count_.read_vec<int32_t>(size_t(n_rays));
  std::vector<int32_t> offset(size_t(n_rays) + 1, 0);
  for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + count[size_t(r)];
  offset_.write_vec(offset);
  live.row_rays(n_rays, offset_, row_ray_);
  gather_.set_args(n_rays, M, kDensStride, live.offsets(), begin_, offset_, dens, dens_b_, 1);
  gather_.launch({global}, {64});
  return offset.back();
}

void HeadBand::expand_head(int n_rays, int M, cl::Buffer& head) {
  expand_.set_args(n_rays, M, kOffLogit, begin_, offset_, head_b_, head);
  expand_.launch({cl::round_up(size_t(n_rays) * size_t(M), 64)}, {64});
}

void HeadBand::gather_head_gradient(int n_rays, int M, const SampleCompaction& live,
                                    const cl::Buffer& g_head) {
  gather_.set_args(n_rays, M, 2, live.offsets(), begin_, offset_, g_head, g_head_b_, 0);
  gather_.launch({cl::round_up(size_t(n_rays * M), 64)}, {64});
}

void HeadBand::scatter_density_gradient(int n_rays, int M, const SampleCompaction& live,
                                        cl::Buffer& g_dens) {
  scatter_.set_args(n_rays, M, kDensStride, live.offsets(), begin_, offset_, g_dens_b_, g_dens);
  scatter_.launch({cl::round_up(size_t(n_rays * M), 64)}, {64});
}

}  // namespace sgnlf::pipeline
