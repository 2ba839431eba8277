// LidarNerfModel: which samples the field evaluates (method.md §0; issue 19): the uniform and
// importance samples, the coarse pass (in waves with render.coarse_waves), early ray
// termination's compaction of the live samples, and the LiDAR head's weight band.
#include <algorithm>

#include "core/error.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/model_constants.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

int LidarNerfModel::sample(int n_rays, bool jitter, uint64_t seed, uint32_t step) {
  const int S = cfg_.render.n_samples, I = cfg_.render.n_importance;
  const int n_c = n_rays * S;
  encoded_ = false;
  compacted_ = false;
  fwd_rays_ = 0;  // a new forward: forward_rays()'s activations are gone
  n_live_ = long(n_rays) * (S + I);
  n_coarse_ = 0;
  n_band_ = 0;
  const bool terminate = cfg_.render.stop_transmittance > 0.0f;
  if (I == 0 && !terminate) {
    sampler_.uniform(o_, d_, n_rays, jitter, seed, step, t_, x_);
    clamp_.set_args(n_c * 3, kSceneBound, x_);
    clamp_.launch({cl::round_up(size_t(n_c) * 3, 64)}, {64});
    return S;
  }
  // Coarse pass (densities only, no gradient), then importance samples merged with it.
  sampler_.uniform(o_, d_, n_rays, jitter, seed, step, t_c_, x_c_);
  clamp_.set_args(n_c * 3, kSceneBound, x_c_);
  clamp_.launch({cl::round_up(size_t(n_c) * 3, 64)}, {64});
  if (waves_ > 1) {
    coarse_waves(n_rays);
  } else {
    encoder_->forward(params_, off_grid_, x_c_, n_c, enc_c_);
    density_.forward(params_, off_density_, enc_c_, n_c, dens_, density_ctx_);
    col_get_.set_args(n_c, kDensStride, 0, dens_, h0_);
    col_get_.launch({cl::round_up(size_t(n_c), 64)}, {64});
    renderer_.weights(t_c_, h0_, n_rays, S, w_c_);
    n_coarse_ = n_c;
  }
  if (I == 0) {
    // Early termination of uniform-only sampling (GeoNLF's, SG-NLF's): the pass above found
    // each ray's termination point; the sample set is the same uniform one (drawn again: the
    // same seed and step give the same samples), and its live prefix reuses the pass's
    // encodings (enc_c_: the layout of S samples per ray is the merged layout here).
    sampler_.uniform(o_, d_, n_rays, jitter, seed, step, t_, x_);
    clamp_.set_args(n_c * 3, kSceneBound, x_);
    clamp_.launch({cl::round_up(size_t(n_c) * 3, 64)}, {64});
    encoded_ = reuse_coarse_;
    compact(n_rays, S);
    return S;
  }
  sampler_.importance(o_, d_, n_rays, S, t_c_, w_c_, jitter, seed, step, t_, x_, src_);
  const int M = S + I, n = n_rays * M;
  clamp_.set_args(n * 3, kSceneBound, x_);
  clamp_.launch({cl::round_up(size_t(n) * 3, 64)}, {64});
  // The merged set's coarse samples were encoded above with the same parameters: only the
  // importance samples need the hash grid (exact; the coarse positions are copied over so that
  // the backward scatters where the forward read).
  const size_t global = cl::round_up(size_t(n), 64);
  if (reuse_coarse_) {
    fine_points_.set_args(n_rays, S, M, src_, x_, x_f_);
    fine_points_.launch({global}, {64});
    encoder_->forward(params_, off_grid_, x_f_, n_rays * I, enc_f_);
  }
  const int lf = encoder_->width();
  merge_.set_args(n_rays, S, M, lf, src_, x_c_, enc_c_, enc_f_, x_, enc_);
  merge_.launch({global}, {64});
  encoded_ = reuse_coarse_;
  if (cfg_.render.stop_transmittance > 0.0f) compact(n_rays, M);
  return M;
}

void LidarNerfModel::coarse_waves(int n_rays) {
  const int S = cfg_.render.n_samples, n_c = n_rays * S, lf = encoder_->width();
  const float eps = cfg_.render.stop_transmittance;
  fill_.set_args(n_c, kDeadLogit, h0_);
  fill_.launch({cl::round_up(size_t(n_c), 64)}, {64});
  std::vector<int32_t> alive(static_cast<size_t>(n_rays));
  for (int r = 0; r < n_rays; ++r) alive[size_t(r)] = r;
  n_coarse_ = 0;
  for (int k = 0; k < waves_ && !alive.empty(); ++k) {
    // Wave k: coarse samples [s0, s1) of the rays still alive (an even split of S).
    const int s0 = int(long(S) * k / waves_), s1 = int(long(S) * (k + 1) / waves_);
    const int width = s1 - s0, n_alive = int(alive.size()), rows = n_alive * width;
    alive_.write(alive.data(), alive.size() * sizeof(int32_t));
    const size_t global = cl::round_up(size_t(rows), 64);
    wave_gather_.set_args(n_alive, S, s0, width, alive_, x_c_, x_w_);
    wave_gather_.launch({global}, {64});
    encoder_->forward(params_, off_grid_, x_w_, rows, enc_w_);
    density_.forward(params_, off_density_, enc_w_, rows, dens_, density_ctx_);
    wave_scatter_.set_args(n_alive, S, s0, width, lf, kDensStride, alive_, enc_w_, dens_, enc_c_,
                           h0_);
    wave_scatter_.launch({global}, {64});
    n_coarse_ += rows;
    renderer_.weights(t_c_, h0_, n_rays, S, w_c_);
    if (k + 1 == waves_) break;
    // One host sync per wave: which rays go on (their termination index is not below s1).
    wave_done_.set_args(n_rays, S, s1, eps, w_c_, done_);
    wave_done_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
    const std::vector<int32_t> done = done_.read_vec<int32_t>(size_t(n_rays));
    std::vector<int32_t> next;
    next.reserve(alive.size());
    for (int32_t r : alive)
      if (!done[size_t(r)]) next.push_back(r);
    alive.swap(next);
  }
}

void LidarNerfModel::compact(int n_rays, int M) {
  const int S = cfg_.render.n_samples;
  live_count_.set_args(n_rays, S, M, cfg_.render.stop_transmittance, t_c_, w_c_, t_, count_);
  live_count_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
  // The one host sync of the step before the loss: kernel sizes below depend on the total.
  const std::vector<int32_t> count = count_.read_vec<int32_t>(size_t(n_rays));
  std::vector<int32_t> offset(size_t(n_rays) + 1, 0);
  for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + count[size_t(r)];
  n_live_ = offset.back();
  offset_.write_vec(offset);
  row_ray_k_.set_args(n_rays, offset_, row_ray_);
  row_ray_k_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
  const size_t global = cl::round_up(size_t(n_rays) * M, 64);
  compact_rows_.set_args(n_rays, M, 3, offset_, x_, x_l_);
  compact_rows_.launch({global}, {64});
  const int n = int(n_live_);
  if (encoded_) {
    const int lf = encoder_->width();
    // Uniform-only sampling keeps its encodings in the coarse buffer (same layout, M = S).
    const cl::Buffer& enc = cfg_.render.n_importance == 0 ? enc_c_ : enc_;
    compact_rows_.set_args(n_rays, M, lf, offset_, enc, enc_l_);
    compact_rows_.launch({global}, {64});
  } else {
    encoder_->forward(params_, off_grid_, x_l_, n, enc_l_);
  }
  compacted_ = true;
}

std::vector<int> LidarNerfModel::live_counts() const {
  if (!compacted_) throw Error("LidarNerfModel::live_counts: the last pass did not terminate rays early");
  const auto offset = offset_.read_vec<int32_t>(size_t(ray_count_) + 1);
  std::vector<int> c(static_cast<size_t>(ray_count_), 0);
  for (size_t r = 0; r < c.size(); ++r) c[r] = offset[r + 1] - offset[r];
  return c;
}


void LidarNerfModel::head_band(int n_rays, int M) {
  const size_t global = cl::round_up(size_t(n_rays) * size_t(M), 64);
  // σ logits into the full layout (the head outputs written here are replaced below), then the
  // weights the band is cut from: the renderer's own (same kernel arithmetic as its forward).
  expand_.set_args(n_rays, M, kDensStride, kDeadLogit, offset_, dens_, head_l_, h0_, head_out_);
  expand_.launch({global}, {64});
  renderer_.weights(t_, h0_, n_rays, M, weights_);
  band_k_.set_args(n_rays, M, band_thr_, offset_, weights_, band_begin_, band_count_);
  band_k_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
  // The step's second host sync: the band's size sets the head's row count.
  const std::vector<int32_t> count = band_count_.read_vec<int32_t>(size_t(n_rays));
  std::vector<int32_t> offset(size_t(n_rays) + 1, 0);
  for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + count[size_t(r)];
  n_band_ = offset.back();
  band_offset_.write_vec(offset);
  row_ray_k_.set_args(n_rays, band_offset_, band_row_ray_);
  row_ray_k_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
  band_gather_.set_args(n_rays, M, kDensStride, offset_, band_begin_, band_offset_, dens_, dens_b_, 1);
  band_gather_.launch({global}, {64});
  const field::GroupIndex index{&band_row_ray_, &band_offset_, n_rays};
  head_.forward(params_, off_head_, dens_b_, int(n_band_), head_b_, head_ctx_, &dir_enc_, 1, &index);
  band_expand_.set_args(n_rays, M, kOffLogit, band_begin_, band_offset_, head_b_, head_out_);
  band_expand_.launch({global}, {64});
  banded_ = true;
}

}  // namespace sgnlf::pipeline
