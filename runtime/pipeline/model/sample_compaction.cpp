// SampleCompaction: launches kernels/pipeline/sample_compaction.cl.
#include "pipeline/model/sample_compaction.hpp"

#include <cstdint>
#include <functional>
#include <string>

#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

namespace {
constexpr size_t kOffsetsWg = 256;  // OFFSETS_WG of kernels/pipeline/sample_compaction.cl
}

// `count` launches the live counts into the buffer it is given; run() turns them into the per-ray
// offsets (n_rays + 1 int32s) and returns the total, the step's one host sync before the loss:
// the kernel sizes after it depend on it.
class SampleCompaction::OffsetSum {
 public:
  virtual ~OffsetSum() = default;
  virtual long run(int n_rays, const std::function<void(cl::Buffer&)>& count,
                   cl::Buffer& offset) = 0;
};

// compaction: host: the counts read back, summed on the host and the offsets written back.
class SampleCompaction::HostOffsetSum final : public OffsetSum {
 public:
  HostOffsetSum(cl::Runtime& rt, int max_rays) : count_(floats(rt, size_t(max_rays))) {}
  long run(int n_rays, const std::function<void(cl::Buffer&)>& count,
           cl::Buffer& offset) override {
    count(count_);
    const std::vector<int32_t> c = count_.read_vec<int32_t>(size_t(n_rays));
    std::vector<int32_t> o(size_t(n_rays) + 1, 0);
    for (int r = 0; r < n_rays; ++r) o[size_t(r) + 1] = o[size_t(r)] + c[size_t(r)];
    offset.write_vec(o);
    return o.back();
  }

 private:
  cl::Buffer count_;
};

// compaction: device: the counts straight into the offsets, scanned there in one work-group;
// only the total (4 bytes) is read.
class SampleCompaction::DeviceOffsetSum final : public OffsetSum {
 public:
  explicit DeviceOffsetSum(cl::Runtime& rt)
      : scan_k_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_offsets_scan")) {}
  long run(int n_rays, const std::function<void(cl::Buffer&)>& count,
           cl::Buffer& offset) override {
    count(offset);
    scan_k_.set_args(n_rays, offset);
    scan_k_.launch({kOffsetsWg}, {kOffsetsWg});
    int32_t total = 0;
    offset.read(&total, sizeof total, size_t(n_rays) * sizeof total);
    return total;
  }

 private:
  cl::Kernel scan_k_;
};

SampleCompaction::~SampleCompaction() = default;

SampleCompaction::SampleCompaction(cl::Runtime& rt, int max_rays, int max_samples, int n_samples,
                                   int width, float eps)
    : S_(n_samples),
      width_(width),
      eps_(eps),
      live_count_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_live_count")),
      compact_rows_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_compact_rows")),
      expand_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_expand_outputs")),
      row_ray_k_(rt.kernel("pipeline/sample_compaction.cl", "pipeline_row_ray")),
      ray_wi_(rt.device_profile().ray_work_items),
      ray_wg_(rt.device_profile().local_size) {
  if (rt.device_profile().compaction == cl::CompactionScan::Device)
    sum_ = std::make_unique<DeviceOffsetSum>(rt);
  else
    sum_ = std::make_unique<HostOffsetSum>(rt, max_rays);
  if (ray_wi_ > 1) {
    // The gpu profile's ray_work_items work-items per ray for the counts and the row → ray map
    // (integer results, the same as the per-ray kernels'), in work-groups of local_size.
    const std::string opt =
        "-DRAY_WI=" + std::to_string(ray_wi_) + " -DRAY_WG=" + std::to_string(ray_wg_);
    live_count_ = rt.kernel("pipeline/sample_compaction.cl", "pipeline_live_count_wide", opt);
    row_ray_k_ = rt.kernel("pipeline/sample_compaction.cl", "pipeline_row_ray_wide", opt);
  }
  const size_t R = size_t(max_rays), N = R * size_t(max_samples);
  offset_ = floats(rt, R + 1), row_ray_ = floats(rt, N);
  x_l_ = floats(rt, N * 3), enc_l_ = floats(rt, N * size_t(width)), head_l_ = floats(rt, N * 2);
  g_h0_l_ = floats(rt, N), g_head_l_ = floats(rt, N * 2);
}

long SampleCompaction::select(int n_rays, int M, const cl::Buffer& t_c, const cl::Buffer& w_c,
                              const cl::Buffer& t, const cl::Buffer& x) {
  rows_ = sum_->run(
      n_rays,
      [&](cl::Buffer& counts) {
        live_count_.set_args(n_rays, S_, M, eps_, t_c, w_c, t, counts);
        launch_live_count(n_rays);
      },
      offset_);
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
