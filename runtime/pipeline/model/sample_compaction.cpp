// SampleCompaction: launches kernels/pipeline/sample_compaction.cl.
#include "pipeline/model/sample_compaction.hpp"

#include <cstdint>
#include <string>

#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

namespace {
constexpr size_t kOffsetsWg = 256;  // OFFSETS_WG of kernels/pipeline/sample_compaction.cl
}

SampleCompaction::SampleCompaction(cl::Runtime& rt, int max_rays, int max_samples, int n_samples,
                                   int width, float eps)
    : S_(n_samples),
      width_(width),
      eps_(eps),
      live_count_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_live_count")),
      compact_rows_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_compact_rows")),
      expand_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_expand_outputs")),
      row_ray_k_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_row_ray")),
      device_scan_(rt.device_profile().compaction == cl::CompactionScan::Device),
      ray_wi_(rt.device_profile().ray_work_items),
      ray_wg_(rt.device_profile().local_size) {
  if (device_scan_) scan_k_ = rt.kernel("pipeline/sample_compaction.cl", "pipeline_offsets_scan");
  if (ray_wi_ > 1) {
    // The gpu profile's ray_work_items work-items per ray for the counts and the row → ray map
    // (integer results, the same as the per-ray kernels'), in work-groups of local_size.
    const std::string opt =
        "-DRAY_WI=" + std::to_string(ray_wi_) + " -DRAY_WG=" + std::to_string(ray_wg_);
    live_count_ = rt.kernel("pipeline/sample_compaction.cl", "pipeline_live_count_wide", opt);
    row_ray_k_ = rt.kernel("pipeline/sample_compaction.cl", "pipeline_row_ray_wide", opt);
  }
  const size_t R = size_t(max_rays), N = R * size_t(max_samples);
  count_ = floats(rt, R), offset_ = floats(rt, R + 1), row_ray_ = floats(rt, N);
  x_l_ = floats(rt, N * 3), enc_l_ = floats(rt, N * size_t(width)), head_l_ = floats(rt, N * 2);
  g_h0_l_ = floats(rt, N), g_head_l_ = floats(rt, N * 2);
}

long SampleCompaction::select(int n_rays, int M, const cl::Buffer& t_c, const cl::Buffer& w_c,
                              const cl::Buffer& t, const cl::Buffer& x) {
  if (device_scan_) {
    // The counts straight into the offsets, scanned there; the one host sync of the step before
    // the loss is the total (4 bytes): the kernel sizes below depend on it.
    live_count_.set_args(n_rays, S_, M, eps_, t_c, w_c, t, offset_);
    launch_live_count(n_rays);
    scan_k_.set_args(n_rays, offset_);
    scan_k_.launch({kOffsetsWg}, {kOffsetsWg});
    int32_t total = 0;
    offset_.read(&total, sizeof total, size_t(n_rays) * sizeof total);
    rows_ = total;
  } else {
    live_count_.set_args(n_rays, S_, M, eps_, t_c, w_c, t, count_);
    launch_live_count(n_rays);
    // The one host sync of the step before the loss: kernel sizes below depend on the total.
    const std::vector<int32_t> count = count_.read_vec<int32_t>(size_t(n_rays));
    std::vector<int32_t> offset(size_t(n_rays) + 1, 0);
    for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + count[size_t(r)];
    rows_ = offset.back();
    offset_.write_vec(offset);
  }
  row_rays(n_rays, offset_, row_ray_);
  compact_rows_.set_args(n_rays, M, 3, offset_, x, x_l_);
  compact_rows_.launch({cl::round_up(size_t(n_rays) * M, 64)}, {64});
  return rows_;
}

void SampleCompaction::gather_encodings(int n_rays, int M, const cl::Buffer& enc) {
  compact_rows_.set_args(n_rays, M, width_, offset_, enc, enc_l_);
  compact_rows_.launch({cl::round_up(size_t(n_rays) * M, 64)}, {64});
}

void SampleCompaction::encode(field::Encoder& encoder, const cl::Buffer& params, size_t offset) {
  encoder.forward(params, offset, x_l_, int(rows_), enc_l_);
}

void SampleCompaction::expand(int n_rays, int M, const cl::Buffer& dens, cl::Buffer& h0,
                              cl::Buffer& head) {
  expand_.set_args(n_rays, M, kDensStride, kDeadLogit, offset_, dens, head_l_, h0, head);
  expand_.launch({cl::round_up(size_t(n_rays) * size_t(M), 64)}, {64});
}

void SampleCompaction::gather_gradients(int n_rays, int M, const cl::Buffer& g_h0,
                                        const cl::Buffer* g_head) {
  const size_t global = cl::round_up(size_t(n_rays * M), 64);
  compact_rows_.set_args(n_rays, M, 1, offset_, g_h0, g_h0_l_);
  compact_rows_.launch({global}, {64});
  if (g_head) {
    compact_rows_.set_args(n_rays, M, 2, offset_, *g_head, g_head_l_);
    compact_rows_.launch({global}, {64});
  }
}

void SampleCompaction::launch_live_count(int n_rays) {
  if (ray_wi_ == 1) {
    live_count_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
    return;
  }
  const size_t wg = size_t(ray_wg_), rays_per_group = wg / size_t(ray_wi_);
  live_count_.launch({(size_t(n_rays) + rays_per_group - 1) / rays_per_group * wg}, {wg});
}

void SampleCompaction::row_rays(int n_rays, const cl::Buffer& offset, cl::Buffer& ray) {
  row_ray_k_.set_args(n_rays, offset, ray);
  const size_t n = size_t(n_rays) * size_t(ray_wi_);
  row_ray_k_.launch({cl::round_up(n, 64)}, {64});
}

std::vector<int> SampleCompaction::counts(int n_rays) const {
  const auto offset = offset_.read_vec<int32_t>(size_t(n_rays) + 1);
  std::vector<int> c(static_cast<size_t>(n_rays), 0);
  for (size_t r = 0; r < c.size(); ++r) c[r] = offset[r + 1] - offset[r];
  return c;
}

}  // namespace sgnlf::pipeline
