// LidarNerfModel: composition of the field and render launchers, the samplers (sampler.hpp) and
// the loss terms (loss_terms.hpp) into one training step, sample → forward → losses →
// backward (method.md §0–1). Sample-major buffers hold max_rays × max(n_samples +
// n_importance, surface samples) samples.
#include "pipeline/model/model.hpp"

#include "pipeline/model/model_detail.hpp"

#include "core/error.hpp"
#include "field/hash_grid_encoder.hpp"
#include "field/lidar4d_encoder.hpp"
#include "spectral/hybrid_encoder.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;
namespace {

// LiDAR head on [geo, dir_enc] (method.md §0) with the direction encoding as a grouped input:
// the same function and parameter layout as an MLP on the 87-wide concatenation, but the
// direction part of the first layer is computed once per ray; the 15 geometric features are
// read in place from columns 1..15 of the density output. With LiDAR4D's separate heads
// (lidar4d.separate_heads) it is two towers of head_hidden each, the return probability's and
// the intensity's: two separate networks on the same input (field::MlpSpec::towers).
field::MlpSpec head_spec(const TrainConfig& c) {
  const FieldSizes& f = c.field;
  const int towers = c.lidar4d && c.lidar4d->separate_heads ? 2 : 1;
  field::MlpSpec s = field::make_mlp_spec(f.geo_features, towers * f.head_hidden, f.head_layers,
                                          2, field::Activation::Relu);
  s.towers = towers;
  s.n_in_group = 6 * f.dir_frequencies;
  s.in_stride = kDensStride;
  s.in_offset = 1;
  return s;
}

// The position encoder of `c`; `hybrid` points at it when it is SG-NLF's hybrid one.
std::unique_ptr<field::Encoder> make_encoder(cl::Runtime& rt, const TrainConfig& c,
                                             spectral::HybridEncoder*& hybrid,
                                             field::Lidar4DEncoder*& four_d) {
  if (c.four_d_encoder()) {
    if (c.hybrid_encoder())
      throw ConfigError("config: the 'lidar4d' and 'spectral' encoders exclude each other");
    auto e = std::make_unique<field::Lidar4DEncoder>(rt, c.lidar4d->encoder);
    four_d = e.get();
    return e;
  }
  if (c.hybrid_encoder()) {
    auto e = std::make_unique<spectral::HybridEncoder>(rt, c.field.grid, c.spectral->psi,
                                                       c.spectral->loss, c.spectral->geometric);
    hybrid = e.get();
    return e;
  }
  return std::make_unique<field::HashGridEncoder>(rt, c.field.grid);
}

}  // namespace

LidarNerfModel::LidarNerfModel(cl::Runtime& rt, const TrainConfig& c, float scene_scale,
                               int max_rays)
    : rt_(rt),
      cfg_(c),
      max_rays_(max_rays),
      encoder_(make_encoder(rt, c, hybrid_, four_d_)),
      density_(rt, field::make_mlp_spec(encoder_->width(),
                                        c.field.density_hidden, 1, 1 + c.field.geo_features,
                                        field::Activation::Relu)),
      head_(rt, head_spec(c)),
      dirs_(rt, c.field.dir_frequencies, c.field.geo_features, 1, 1 + c.field.geo_features),
      sampler_(rt, c.render, scene_scale),
      renderer_(rt, c.render, scene_scale),
      loss_(rt, c.render, scene_scale,
            c.lidar4d ? float(c.lidar4d->ray_drop_label_smoothing) : 0.0f),
      ray_grad_(rt) {
  if (1 + c.field.geo_features != kDensStride)
    throw ConfigError("config.field: 'geo_features' must be 15 (density output 1 + 15 = 16)");
  off_grid_ = layout_.add("hash_grid", encoder_->n_params()).offset;
  off_density_ = layout_.add("density_mlp", density_.n_params()).offset;
  off_head_ = layout_.add("head_mlp", head_.n_params()).offset;
  col_get_ = rt.kernel("field/columns.cl", "field_column_get");
  col_set_ = rt.kernel("field/columns.cl", "field_column_set");
  clamp_ = rt.kernel("render/sample.cl", "render_clamp_points");

  // The samplers by name (sampler.hpp): the protocol's for every pass, the training rays'.
  const auto& rc = c.render;
  const std::string protocol_name = rc.sampler_name(), training_name = rc.training_sampler_name();
  const SamplerKind& protocol = find_sampler(protocol_name, "render.sampler", rc);
  const SamplerKind& training = find_sampler(training_name, "render.training_sampler", rc);
  const size_t R = size_t(max_rays), S = size_t(rc.n_samples),
               M = std::max({S + size_t(rc.n_importance), size_t(protocol.per_ray(rc)),
                             size_t(training.per_ray(rc))}),
               N = R * M;
  samples_cap_ = int(M);
  const size_t lf = size_t(encoder_->width());
  const size_t enc_dim = size_t(dirs_.enc_dim());
  params_ = floats(rt, layout_.total());
  grad_ = floats(rt, layout_.total());
  grad_.fill_zero();
  o_ = floats(rt, R * 3), d_ = floats(rt, R * 3), target_ = floats(rt, R * 3);
  t_c_ = floats(rt, R * S), x_c_ = floats(rt, R * S * 3), w_c_ = floats(rt, R * S);
  enc_c_ = floats(rt, R * S * lf);
  t_ = floats(rt, N), x_ = floats(rt, N * 3), enc_ = floats(rt, N * lf);
  dens_ = floats(rt, N * kDensStride), h0_ = floats(rt, N);
  dir_enc_ = floats(rt, R * enc_dim), head_out_ = floats(rt, N * 2);
  out_ = floats(rt, R * 3), weights_ = floats(rt, N), grad_out_ = floats(rt, R * 3);
  terms_ = floats(rt, R * 3), loss_buf_ = floats(rt, kLossBufferFloats);
  g_h0_ = floats(rt, N), g_head_ = floats(rt, N * 2);
  g_dens_ = floats(rt, N * kDensStride), g_enc_ = floats(rt, N * lf);
  g_dir_enc_ = floats(rt, R * enc_dim);
  // The launchers the samplers share with the forward and the fast renderer (SamplerParts);
  // the head band only with early termination.
  const int width = encoder_->width();
  if (rc.n_importance > 0)
    reuse_ = std::make_unique<EncodingReuse>(rt, max_rays, rc.n_samples, rc.n_importance, width);
  if (rc.stop_transmittance > 0.0f) {
    live_ = std::make_unique<SampleCompaction>(rt, max_rays, int(M), rc.n_samples, width,
                                                rc.stop_transmittance);
    if (rc.head_weight_threshold > 0.0f)
      band_ = std::make_unique<HeadBand>(rt, max_rays, int(M), rc.head_weight_threshold);
  }
  if (rc.weights.carve > 0.0f)
    carve_ = std::make_unique<render::WeightCarving>(rt, rc, scene_scale, max_rays);
  loss_buf_.fill_zero();
  scene_scale_ = scene_scale;
  set_reuse_coarse_encodings(reuse_coarse_);  // off for the 4D encoder (see model.hpp)
  // The samplers on the launchers above, the buffers and the field's density-only pass.
  const SamplerParts parts{sampler_, reuse_.get(), live_.get()};
  const SampleBuffers buffers{o_, d_, target_, t_c_, x_c_, w_c_, enc_c_, t_, x_, enc_, h0_};
  const SamplerField field{
      *encoder_, params_, off_grid_,
      [this](const cl::Buffer& x, int rows, cl::Buffer& enc) -> const cl::Buffer& {
        encoder_->forward(params_, off_grid_, x, rows, enc);
        density_.forward(params_, off_density_, enc, rows, dens_, density_ctx_);
        return dens_;
      },
      [this](const cl::Buffer& dens, int rows, cl::Buffer& h0) {
        col_get_.set_args(rows, kDensStride, 0, dens, h0);
        col_get_.launch({cl::round_up(size_t(rows), 64)}, {64});
      },
      [this](const cl::Buffer& t, const cl::Buffer& h0, int n_rays, int S, cl::Buffer& w) {
        renderer_.weights(t, h0, n_rays, S, w);
      },
      [this](cl::Buffer& x, int rows) {
        clamp_.set_args(rows * 3, kSceneBound, x);
        clamp_.launch({cl::round_up(size_t(rows) * 3, 64)}, {64});
      }};
  const SamplerContext context{rt, cfg_.render, scene_scale, max_rays, width, parts, buffers, field};
  protocol_ = make_sampler(protocol_name, "render.sampler", context);
  training_ = protocol_.get();
  if (training_name != protocol_name) {
    training_sampler_ = make_sampler(training_name, "render.training_sampler", context);
    training_ = training_sampler_.get();
  }
  losses_ = make_loss_terms(rt, c, scene_scale, loss_, carve_.get());
}

void LidarNerfModel::init_params(uint64_t seed) {
  std::vector<float> p(layout_.total(), 0.0f);
  encoder_->init_params(p, off_grid_, seed ^ 0x1111);
  density_.init_params(p, off_density_, seed ^ 0x2222);
  head_.init_params(p, off_head_, seed ^ 0x3333);
  params_.write_vec(p);
}

SampleSet LidarNerfModel::sample(Sampler& s, int n_rays, bool jitter, uint64_t seed,
                                 uint32_t step) {
  last_ = ForwardContext{};
  last_.pass = begin_pass();
  stats_rays_ = 0;
  SampleRequest r;
  r.n_rays = n_rays, r.jitter = jitter, r.seed = seed, r.step = step;
  r.reuse_encodings = reuse_coarse_;
  last_.samples = s.sample(r);
  last_.samples.strategy = s.name();
  return last_.samples;
}

ForwardContext LidarNerfModel::forward(const SampleSet& s) {
  const int n_rays = s.n_rays, samples = s.per_ray, n = n_rays * samples;
  ForwardContext ctx;
  ctx.samples = s;
  ctx.pass = pass_;
  // With early termination the field runs on the live rows only (live_); the renderer always
  // sees the full layout, dead samples at zero density.
  const int rows = int(s.rows);
  if (!s.encoded) encoder_->forward(params_, off_grid_, x_, n, enc_);
  density_.forward(params_, off_density_, s.compacted ? live_->encodings() : enc_, rows, dens_,
                   density_ctx_);
  dirs_.forward(d_, n_rays, dir_enc_);
  if (s.compacted && band_) {
    ctx.head = HeadRows::Band;
    ctx.head_rows = head_band(n_rays, samples);
  } else if (s.compacted) {
    const field::GroupIndex index = live_->index(n_rays);
    head_.forward(params_, off_head_, dens_, rows, live_->head_out(), head_ctx_, &dir_enc_, 1,
                  &index);
    live_->expand(n_rays, samples, dens_, h0_, head_out_);
    ctx.head = HeadRows::Live;
    ctx.head_rows = rows;
  } else {
    col_get_.set_args(n, kDensStride, 0, dens_, h0_);
    col_get_.launch({cl::round_up(size_t(n), 64)}, {64});
    head_.forward(params_, off_head_, dens_, n, head_out_, head_ctx_, &dir_enc_, samples);
    ctx.head = HeadRows::All;
    ctx.head_rows = n;
  }
  renderer_.forward(t_, h0_, head_out_, n_rays, samples, out_, weights_);
  if (last_.pass == ctx.pass) last_ = ctx;
  return ctx;
}

long LidarNerfModel::head_band(int n_rays, int M) {
  // σ logits into the full layout (the head outputs written here are replaced below), then the
  // weights the band is cut from: the renderer's own (same kernel arithmetic as its forward).
  live_->expand(n_rays, M, dens_, h0_, head_out_);
  renderer_.weights(t_, h0_, n_rays, M, weights_);
  // The step's second host sync: the band's size sets the head's row count.
  const long n_band = band_->select(n_rays, M, *live_, weights_, dens_);
  const field::GroupIndex index = band_->index(n_rays);
  head_.forward(params_, off_head_, band_->density(), int(n_band), band_->head_out(), head_ctx_,
                &dir_enc_, 1, &index);
  band_->expand_head(n_rays, M, head_out_);
  return n_band;
}

void LidarNerfModel::forward_backward(const RayBatch& b, uint64_t seed, long step,
                                      bool ray_grads) {
  const int R = b.n_rays;
  require(R > 0 && R <= max_rays_, "LidarNerfModel::forward_backward: batch of " +
                                       std::to_string(R) + " rays, capacity " +
                                       std::to_string(max_rays_));
  // The terms' own passes (loss_term.hpp): each differentiates what it rendered before the next
  // pass overwrites the activations, into the step's second gradient.
  FieldPass own(*this, b, seed, step);
  losses_.each([&](LossTerm& t) { t.add_field_gradient(own); });
  // Non-blocking uploads (the same bytes as blocking writes): the queue reads the host copies
  // when it gets there, behind the previous step's kernels.
  float* target = up_target_.stage<float>(size_t(R) * 3);
  for (int i = 0; i < R; ++i) {
    target[3 * size_t(i)] = b.range[size_t(i)];
    target[3 * size_t(i) + 1] = b.intensity[size_t(i)];
    target[3 * size_t(i) + 2] = b.label[size_t(i)];
  }
  up_target_.write(target_);
  up_o_.write_vec(o_, b.origins);
  up_d_.write_vec(d_, b.directions);
  // The training rays' sampler (render.training_sampler; by the returns with render.surface_*).
  const ForwardContext ctx =
      forward(sample(*training_, R, cfg_.render.jitter, seed, uint32_t(step)));
  // The loss terms (method.md §0–2): the range term writes the per-ray output gradient, the
  // others add theirs; inside the backward, their per-sample ones.
  LossPass pass{b,        step,       R,      ctx.samples.per_ray, out_,   target_, t_, h0_,
                weights_, grad_out_,  terms_, loss_buf_,           g_h0_,  d_};
  losses_.range().write_output_gradient(pass);
  for (const auto& term : losses_.others()) term->add_output_gradient(pass);
  backward(ctx, grad_, ray_grads, &pass);
  // One objective, one gradient: the terms' own passes' share joins the batch's.
  if (own.wrote_gradient()) {
    const int n = int(layout_.total());
    add_k_.set_args(n, grad_own_, grad_);
    add_k_.launch({cl::round_up(size_t(n), 64)}, {64});
  }
  // The terms' own parameter groups (Ψ): their activations of this step are no longer needed.
  OwnGroupStep group(*this, seed, step);
  losses_.each([&](LossTerm& t) { t.take_own_step(group); });
}

void LidarNerfModel::backward(const ForwardContext& ctx, cl::Buffer& grad, bool ray_grads,
                              LossPass* pass) {
  if (!ctx.valid() || ctx.pass != pass_)
    throw Error("LidarNerfModel::backward: the activations of that forward were overwritten by a "
                "later pass");
  const int R = ctx.samples.n_rays, M = ctx.samples.per_ray, n = R * M;
  const bool compacted = ctx.samples.compacted, banded = ctx.head == HeadRows::Band;
  // Backward chain: renderer → head MLP (into columns 1..15 of g_dens_, and per ray into
  // g_dir_enc_) → density MLP → hash grid.
  renderer_.backward(t_, h0_, head_out_, weights_, grad_out_, R, M, g_h0_, g_head_);
  // The loss terms' per-sample gradients on the full layout (weight carving: dead samples have
  // zero weight and get none).
  if (pass) losses_.each([&](LossTerm& t) { t.add_sample_gradient(*pass); });
  // With early termination the chain runs on the live rows: the dead samples' gradients are
  // dropped (they do not exist in the truncated field).
  int rows = n;
  const cl::Buffer *head_y = &head_out_, *g_head = &g_head_, *g_h0 = &g_h0_, *x = &x_;
  if (compacted) {
    rows = int(ctx.samples.rows);
    live_->gather_gradients(R, M, g_h0_, banded ? nullptr : &g_head_);
    head_y = &live_->head_out(), g_head = &live_->grad_head(), g_h0 = &live_->grad_h0();
    x = &live_->positions();
  }
  if (banded) {
    // The head ran on the band rows: its gradient goes into the band layout, then into the
    // live rows (zeros outside the band: the head outputs there are constants).
    band_->gather_head_gradient(R, M, *live_, g_head_);
    head_.backward(params_, off_head_, head_ctx_, band_->head_out(), band_->grad_head(), grad,
                   off_head_, &band_->grad_density(), &g_dir_enc_);
    band_->scatter_density_gradient(R, M, *live_, g_dens_);
  } else {
    head_.backward(params_, off_head_, head_ctx_, *head_y, *g_head, grad, off_head_, &g_dens_,
                   &g_dir_enc_);
  }
  col_set_.set_args(rows, kDensStride, 0, *g_h0, g_dens_);
  col_set_.launch({cl::round_up(size_t(rows), 64)}, {64});
  density_.backward(params_, off_density_, density_ctx_, dens_, g_dens_, grad, off_density_,
                    &g_enc_);
  if (!ray_grads) {
    encoder_->backward(params_, off_grid_, *x, rows, g_enc_, grad, off_grid_, nullptr);
    return;
  }
  if (!g_x_) {  // allocated on the first pose-free step only
    const size_t N = size_t(max_rays_) * size_t(samples_cap_);
    g_x_ = floats(rt_, N * 3);
    g_o_ = floats(rt_, size_t(max_rays_) * 3), g_d_ = floats(rt_, size_t(max_rays_) * 3);
    g_dir_ = floats(rt_, size_t(max_rays_) * 3);
  }
  encoder_->backward(params_, off_grid_, *x, rows, g_enc_, grad, off_grid_, &g_x_);
  ray_grad_.reduce_rows(compacted ? &live_->offsets() : nullptr, t_, o_, d_, g_x_, R, M,
                        kSceneBound, g_o_, g_d_);
  dirs_.backward(d_, R, g_dir_enc_, g_dir_);
  grad_rays_ = R;
}

LidarNerfModel::Trainable LidarNerfModel::trainable() {
  if (four_d_) {  // LiDAR4D's groups: the encodings at lr, the flow field and the MLPs scaled
    const size_t enc_end = off_grid_ + four_d_->offsets().flow;
    return {params_, grad_,
            {{0, enc_end, 1.0}, {enc_end, layout_.total() - enc_end, cfg_.lidar4d->network_lr_scale}}};
  }
  return {params_, grad_, {{0, layout_.total(), 1.0}}};
}

std::vector<float> LidarNerfModel::render_rays(const std::vector<float>& origins,
                                               const std::vector<float>& directions, int n) {
  require(n > 0 && n <= max_rays_, "LidarNerfModel::render_rays: " + std::to_string(n) +
                                       " rays, capacity " + std::to_string(max_rays_));
  o_.write_vec(origins);
  d_.write_vec(directions);
  const int M = forward(sample(*protocol_, n, false, 0, 0)).samples.per_ray;
  if (cfg_.render.eval_depth == "median") renderer_.median_depth(t_, weights_, n, M, out_);
  stats_rays_ = n, stats_samples_ = M;
  return out_.read_vec<float>(size_t(n) * 3);
}

std::vector<float> LidarNerfModel::depth_stats() {
  if (stats_rays_ == 0) throw Error("LidarNerfModel::depth_stats: no render_rays() to describe");
  const int n = stats_rays_, M = stats_samples_;
  if (!stats_median_) {
    stats_median_ = floats(rt_, size_t(max_rays_) * 3);
    stats_spread_ = floats(rt_, size_t(max_rays_) * 2);
  }
  renderer_.median_depth(t_, weights_, n, M, stats_median_);
  renderer_.depth_spread(t_, weights_, n, M, stats_spread_);
  const auto med = stats_median_.read_vec<float>(size_t(n) * 3);
  const auto spread = stats_spread_.read_vec<float>(size_t(n) * 2);
  std::vector<float> out(size_t(n) * 3);
  for (size_t r = 0; r < size_t(n); ++r) {
    out[3 * r] = med[3 * r];
    out[3 * r + 1] = spread[2 * r];
    out[3 * r + 2] = spread[2 * r + 1];
  }
  return out;
}

std::vector<float> LidarNerfModel::encode_points(const std::vector<float>& x, int n) {
  require(n >= 0 && x.size() == size_t(n) * 3,
          "LidarNerfModel::encode_points: " + std::to_string(x.size()) + " floats for " +
              std::to_string(n) + " points");
  const int w = encoder_->width();
  begin_pass();  // x_ and enc_ are overwritten: an earlier pass's activations are gone
  std::vector<float> out(size_t(n) * size_t(w));
  // x_ and enc_ hold max_rays × samples rows.
  const int chunk = max_rays_ * cfg_.render.n_samples;
  for (int b = 0; b < n; b += chunk) {
    const int m = std::min(chunk, n - b);
    x_.write(x.data() + size_t(b) * 3, size_t(m) * 3 * sizeof(float));
    encoder_->forward(params_, off_grid_, x_, m, enc_);
    enc_.read(out.data() + size_t(b) * size_t(w), size_t(m) * size_t(w) * sizeof(float));
  }
  return out;
}

std::vector<float> LidarNerfModel::params() const {
  return params_.read_vec<float>(layout_.total());
}

void LidarNerfModel::set_params(const std::vector<float>& p) {
  if (p.size() != layout_.total())
    throw IoError("model parameters: " + std::to_string(p.size()) + " values, the model has " +
                  std::to_string(layout_.total()));
  params_.write_vec(p);
}

}  // namespace sgnlf::pipeline
