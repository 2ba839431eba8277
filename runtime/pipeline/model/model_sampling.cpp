// LidarNerfModel: which samples the field evaluates (method.md §0): the uniform and
// importance samples, the coarse pass (in waves with render.coarse_waves), early ray
// termination's compaction of the live samples, and the LiDAR head's weight band, each mode
// through its launcher (EncodingReuse, CoarseWaves, SampleCompaction, HeadBand).
#include "core/error.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

int LidarNerfModel::sample(int n_rays, bool jitter, uint64_t seed, uint32_t step) {
  const int S = cfg_.render.n_samples, I = cfg_.render.n_importance;
  const int n_c = n_rays * S;
  encoded_ = false;
  compacted_ = false;
  fwd_rays_ = 0;  // a new forward: forward_rays()'s activations are gone
  stats_rays_ = 0;
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
  if (waves_) {
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
  sampler_.importance(o_, d_, n_rays, S, t_c_, w_c_, jitter, seed, step, t_, x_,
                      reuse_->sources());
  const int M = S + I, n = n_rays * M;
  clamp_.set_args(n * 3, kSceneBound, x_);
  clamp_.launch({cl::round_up(size_t(n) * 3, 64)}, {64});
  // The merged set's coarse samples were encoded above with the same parameters: only the
  // importance samples need the hash grid (exact; the coarse positions are copied over so that
  // the backward scatters where the forward read).
  if (reuse_coarse_) reuse_->encode_importance(n_rays, x_, *encoder_, params_, off_grid_);
  reuse_->merge(n_rays, x_c_, enc_c_, x_, enc_);
  encoded_ = reuse_coarse_;
  if (cfg_.render.stop_transmittance > 0.0f) compact(n_rays, M);
  return M;
}

int LidarNerfModel::sample_surface(int n_rays, bool jitter, uint64_t seed, uint32_t step) {
  const int M = surface_->samples(), n = n_rays * M;
  encoded_ = false;
  compacted_ = false;
  fwd_rays_ = 0;  // a new forward: forward_rays()'s activations are gone
  stats_rays_ = 0;
  n_live_ = long(n);
  n_coarse_ = 0;
  n_band_ = 0;
  surface_->sample(o_, d_, target_, n_rays, jitter, seed, step, t_, x_);
  clamp_.set_args(n * 3, kSceneBound, x_);
  clamp_.launch({cl::round_up(size_t(n) * 3, 64)}, {64});
  return M;
}

void LidarNerfModel::coarse_waves(int n_rays) {
  const int S = cfg_.render.n_samples;
  // Each wave's rows: encodings, then the density MLP into dens_ (its σ logits are scattered
  // into h0_), then the coarse weights of every ray again.
  const auto field = [&](const cl::Buffer& x, int rows, cl::Buffer& enc) -> const cl::Buffer& {
    encoder_->forward(params_, off_grid_, x, rows, enc);
    density_.forward(params_, off_density_, enc, rows, dens_, density_ctx_);
    return dens_;
  };
  const auto weights = [&] { renderer_.weights(t_c_, h0_, n_rays, S, w_c_); };
  n_coarse_ = waves_->run(n_rays, x_c_, w_c_, enc_c_, h0_, field, weights);
}

void LidarNerfModel::compact(int n_rays, int M) {
  n_live_ = live_->select(n_rays, M, t_c_, w_c_, t_, x_);
  if (encoded_) {
    // Uniform-only sampling keeps its encodings in the coarse buffer (same layout, M = S).
    live_->gather_encodings(n_rays, M, cfg_.render.n_importance == 0 ? enc_c_ : enc_);
  } else {
    live_->encode(*encoder_, params_, off_grid_);
  }
  compacted_ = true;
}

std::vector<int> LidarNerfModel::live_counts() const {
  if (!compacted_) throw Error("LidarNerfModel::live_counts: the last pass did not terminate rays early");
  return live_->counts(ray_count_);
}

void LidarNerfModel::head_band(int n_rays, int M) {
  // σ logits into the full layout (the head outputs written here are replaced below), then the
  // weights the band is cut from: the renderer's own (same kernel arithmetic as its forward).
  live_->expand(n_rays, M, dens_, h0_, head_out_);
  renderer_.weights(t_, h0_, n_rays, M, weights_);
  // The step's second host sync: the band's size sets the head's row count.
  n_band_ = band_->select(n_rays, M, *live_, weights_, dens_);
  const field::GroupIndex index = band_->index(n_rays);
  head_.forward(params_, off_head_, band_->density(), int(n_band_), band_->head_out(), head_ctx_,
                &dir_enc_, 1, &index);
  band_->expand_head(n_rays, M, head_out_);
  banded_ = true;
}

}  // namespace sgnlf::pipeline
