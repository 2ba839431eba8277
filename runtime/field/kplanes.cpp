// KPlanes host launcher: plane table, parameter init, validation of shapes and the enqueueing
// of the kernels in kernels/field/kplanes.cl.
#include "field/kplanes.hpp"

#include <algorithm>
#include <string>

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::field {
namespace {
int first_group(PlaneGroups g) { return g == PlaneGroups::Dynamic ? 1 : 0; }
int n_groups(PlaneGroups g) { return g == PlaneGroups::Both ? 2 : 1; }
}  // namespace

std::vector<KPlane> kplanes_layout(const KPlanesConfig& cfg) {
  cfg.validate();
  static const int axis_a[6] = {0, 0, 1, 0, 1, 2}, axis_b[6] = {1, 2, 2, 3, 3, 3};
  std::vector<KPlane> out;
  uint64_t offset = 0;
  for (int s = 0; s < cfg.scales; ++s) {
    const uint32_t res[4] = {uint32_t(cfg.resolution) << s, uint32_t(cfg.resolution) << s,
                             uint32_t(cfg.resolution) << s, uint32_t(cfg.time_resolution)};
    for (int p = 0; p < 6; ++p) {
      KPlane pl;
      pl.scale = s;
      pl.plane = p;
      pl.offset = uint32_t(offset);
      pl.width = res[axis_a[p]];
      pl.height = res[axis_b[p]];
      offset += uint64_t(pl.width) * pl.height;
      out.push_back(pl);
    }
  }
  if (offset * uint64_t(cfg.features) >= (uint64_t(1) << 31))
    throw ConfigError("kplanes: parameter count exceeds 2^31 floats");
  return out;
}

KPlanes::KPlanes(cl::Runtime& rt, const KPlanesConfig& cfg)
    : rt_(rt), cfg_(cfg), planes_(kplanes_layout(cfg)) {
  const auto& last = planes_.back();
  n_params_ = (size_t(last.offset) + size_t(last.width) * last.height) * size_t(cfg_.features);
  std::vector<uint32_t> meta;
  for (const auto& p : planes_) meta.insert(meta.end(), {p.offset, p.width, p.height, 0u});
  meta_ = cl::Buffer::from(rt_, meta);
  chunk_ = cfg_.chunk > 0 ? cfg_.chunk : rt_.device_profile().plane_chunk;
  variant_ = rt_.device_profile().encoder_backward;
  const std::string opt = "-DSCALES=" + std::to_string(cfg_.scales) +
                          " -DFEATURES=" + std::to_string(cfg_.features) +
                          " -DCHUNK=" + std::to_string(chunk_);
  const std::string file = "field/kplanes.cl";
  fwd_ = rt_.kernel(file, "field_kplanes_fwd", opt);
  bwd_ = rt_.kernel(file, "field_kplanes_bwd", opt);
  dx_reduce_ = rt_.kernel(file, "field_kplanes_dx_reduce", opt);
  bwd_points_ = rt_.kernel(file, "field_kplanes_bwd_points", opt);
}

EntryReduction& KPlanes::reduction(PlaneGroups groups) {
  auto& r = reductions_[groups == PlaneGroups::Both ? 0 : (groups == PlaneGroups::Static ? 1 : 2)];
  if (r) return *r;
  // Unit = row s + S·gi (the serial kernel's work-item): the three planes of group
  // first_group + gi at scale s.
  const int g0 = first_group(groups), rows = n_groups(groups) * cfg_.scales;
  std::vector<EntryRange> ranges;
  for (int row = 0; row < rows; ++row) {
    const int s = row % cfg_.scales, gi = row / cfg_.scales;
    for (int k = 0; k < 3; ++k) {
      const KPlane& pl = planes_[size_t(s * 6 + 3 * (g0 + gi) + k)];
      ranges.push_back({uint32_t(row), pl.offset, pl.width * pl.height});
    }
  }
  r = std::make_unique<EntryReduction>(rt_, cfg_.features, rows, 12, 4, std::move(ranges));
  return *r;
}

int KPlanes::n_output(PlaneGroups groups) const {
  return n_groups(groups) * cfg_.scales * cfg_.features;
}

void KPlanes::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const {
  if (offset + n_params_ > host_params.size())
    throw Error("KPlanes::init_params: slice [" + std::to_string(offset) + ", +" +
                std::to_string(n_params_) + ") exceeds buffer of " +
                std::to_string(host_params.size()));
  Rng rng(seed, 0x4b50u);
  const size_t f = size_t(cfg_.features);
  for (const auto& p : planes_) {
    const size_t begin = offset + size_t(p.offset) * f, count = size_t(p.width) * p.height * f;
    for (size_t i = 0; i < count; ++i)
      host_params[begin + i] = p.plane >= 3 ? 1.0f : rng.uniform(cfg_.init_lo, cfg_.init_hi);
  }
}

static void check_bytes(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("KPlanes: buffer '") + what + "' has " + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(floats * sizeof(float)));
}

void KPlanes::check(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                    const cl::Buffer& t, int n, const cl::Buffer& enc, int width, int stride,
                    int col, const char* what) const {
  if (n < 0) throw Error("KPlanes: negative point count " + std::to_string(n));
  if (col < 0 || col + width > stride)
    throw Error("KPlanes: columns [" + std::to_string(col) + ", +" + std::to_string(width) +
                ") do not fit a row of " + std::to_string(stride));
  check_bytes(params, offset + n_params_, "params");
  check_bytes(x, size_t(n) * 3, "x");
  check_bytes(t, size_t(n), "t");
  if (n > 0) check_bytes(enc, size_t(n - 1) * size_t(stride) + size_t(col + width), what);
}

void KPlanes::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                      const cl::Buffer& t, int n, cl::Buffer& enc, PlaneGroups groups, int stride,
                      int col) {
  const int width = n_output(groups);
  if (stride == 0) stride = width;
  check(params, offset, x, t, n, enc, width, stride, col, "enc");
  if (n == 0) return;
  fwd_.set_args(n, params, uint32_t(offset), x, t, meta_, first_group(groups), enc, stride, col);
  launch_points(fwd_, n, n_groups(groups) * cfg_.scales);
}

void KPlanes::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                       const cl::Buffer& t, int n, const cl::Buffer& d_enc, cl::Buffer& grad,
                       size_t grad_offset, cl::Buffer* d_x, PlaneGroups groups, bool accumulate,
                       int stride, int col) {
  const int width = n_output(groups), rows = n_groups(groups) * cfg_.scales;
  if (stride == 0) stride = width;
  check(params, offset, x, t, n, d_enc, width, stride, col, "d_enc");
  check_bytes(grad, grad_offset + n_params_, "grad");
  const bool dx = d_x && n > 0;
  if (dx) {
    check_bytes(*d_x, size_t(n) * 3, "d_x");
    const size_t part = size_t(n) * size_t(rows) * 3;
    if (dx_part_floats_ < part) {
      dx_part_ = cl::Buffer(rt_, part * sizeof(float));
      dx_part_floats_ = part;
    }
  }
  const cl::Buffer& part = dx ? dx_part_ : meta_;  // without d_x never written
  const int g0 = first_group(groups);
  if (variant_ == cl::EncoderBackward::Serial) {
    bwd_.set_args(n, params, uint32_t(offset), x, t, meta_, g0, d_enc, stride, col, grad,
                  uint32_t(grad_offset), accumulate ? 1 : 0, dx ? 1 : 0, part);
    bwd_.launch({size_t(rows)}, {1});
  } else if (variant_ == cl::EncoderBackward::Atomic) {
    if (!accumulate) reduction(groups).zero(grad, grad_offset);
    // The pair buffers are not written by the atomic form: any buffer stands in for them.
    bwd_points_.set_args(n, params, uint32_t(offset), x, t, meta_, g0, d_enc, stride, col, 1,
                         meta_, meta_, meta_, meta_, grad, uint32_t(grad_offset), dx ? 1 : 0,
                         part);
    cl::launch_rows(bwd_points_, size_t(n), size_t(rows));
  } else {
    EntryReduction& r = reduction(groups);
    r.reserve(n);
    if (n > 0) {
      bwd_points_.set_args(n, params, uint32_t(offset), x, t, meta_, g0, d_enc, stride, col, 0,
                           r.keys(), r.vals(), r.coef(), r.vec(), grad, uint32_t(grad_offset),
                           dx ? 1 : 0, part);
      cl::launch_rows(bwd_points_, size_t(n), size_t(rows));
    }
    r.reduce(n, grad, grad_offset, accumulate);
  }
  if (!dx) return;
  dx_reduce_.set_args(n, rows, dx_part_, *d_x);
  cl::launch_1d(dx_reduce_, size_t(n));
}

void KPlanes::launch_points(cl::Kernel& k, int n, int rows) {
  const size_t items = (size_t(n) + size_t(chunk_) - 1) / size_t(chunk_);
  if (chunk_ == 1)
    cl::launch_rows(k, items, size_t(rows));
  else
    k.launch({items, size_t(rows)}, {1, 1});
}

}  // namespace sgnlf::field
