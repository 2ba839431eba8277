// The LiDAR-NeRF model on the device (method.md §0–1): position encoder (field::Encoder: the
// hash grid, or SG-NLF's hybrid [f_geo, λ·Ψ]) → density MLP (σ logit + 15 geometric features)
// → [geo, direction encoding] → LiDAR head → volume rendering, the training losses and the
// backward chain into the gradient of one flat parameter buffer. The optimiser that steps that
// buffer is the training step's (train/field_optimizer.hpp), not the model's.
//
// Every pass is sample → forward → (losses →) backward:
// - a Sampler (sampler.hpp) places the pass's samples and returns a SampleSet: the strategy
//   registered under the config's name, render.sampler for every pass (by default the
//   protocol's: uniform; importance with the coarse encodings reused; early termination's live
//   rows, its coarse pass in waves) and render.training_sampler for training rays (by default
//   samples by the return with render.surface_*);
// - the forward runs the field on that set (the head on every row, the live rows, or the head
//   band of render.head_weight_threshold) and returns a ForwardContext (forward_context.hpp):
//   what the backward needs, and the pass number that says whether the activations are still
//   this forward's;
// - the loss terms (loss_term.hpp; the config's in loss_terms.hpp: range, patch gradient,
//   Chamfer, weight carving; a step part's: the cross-frame consistency, the flow supervision,
//   which run a pass of their own first) each add
//   their gradient, per ray or per sample, and report their values;
// - the backward takes that context and the gradient through renderer → head → density →
//   encoder into a parameter gradient (and the rays' gradients for the pose-free methods).
// A training step is enqueued as a whole; the only host sync is the caller's loss read-back
// (and those of early termination, the head band and the Chamfer term).
// The model owns the field and render launchers and the launchers its forward shares with
// the samplers (EncodingReuse, SampleCompaction) or uses alone (HeadBand); a sampler owns the
// launchers only it uses (CoarseWaves, render::SurfaceSampler).
#pragma once
#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "cl/staged_upload.hpp"
#include "field/dir_encoding.hpp"
#include "field/encoder.hpp"
#include "field/mlp.hpp"
#include "field/param_layout.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/model/coarse_waves.hpp"
#include "pipeline/model/encoding_reuse.hpp"
#include "pipeline/model/fast_march.hpp"
#include "pipeline/model/grid_march.hpp"
#include "pipeline/model/forward_context.hpp"
#include "pipeline/model/head_band.hpp"
#include "pipeline/model/loss_terms.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/model/sample_compaction.hpp"
#include "pipeline/model/sampler.hpp"
#include "render/pose_grad_sums.hpp"
#include "render/range_loss.hpp"
#include "render/ray_gradient.hpp"
#include "render/ray_sampler.hpp"
#include "render/weight_carving.hpp"
#include "render/volume_renderer.hpp"

namespace sgnlf::spectral {
class HybridEncoder;
}
namespace sgnlf::field {
class Lidar4DEncoder;
class SceneFlow;
}

namespace sgnlf::pipeline {

class LidarNerfModel {
 public:
  // `max_rays`: the largest ray count of one call (training batch or render chunk).
  LidarNerfModel(cl::Runtime& rt, const TrainConfig& c, float scene_scale, int max_rays);

  size_t n_params() const { return layout_.total(); }
  const field::ParamLayout& layout() const { return layout_; }
  // Deterministic initialisation from `seed` (hash grid ±1e-4, MLP fan-in uniform).
  void init_params(uint64_t seed);

  // The field's part of a training step: enqueues the step's gradient through the list of loss
  // terms (loss_term.hpp: the terms' own passes, then the batch's sampling, forward, loss and
  // backward, the two gradients summed) into the gradient buffer (and, with `ray_grads`,
  // dL/d(origin) and dL/d(direction) of every batch ray for the pose-free methods, read with
  // read_ray_grads()). The step's optimiser (train/field_optimizer.hpp) then steps trainable().
  // No wait (but what a term's own pass reads back).
  void forward_backward(const RayBatch& b, uint64_t seed, long step, bool ray_grads = false);

  // The field's parameters (layout()): a blocking read, and a write that checks the count
  // (IoError naming both).
  std::vector<float> params() const;
  void set_params(const std::vector<float>& p);
  // What an optimiser steps: the parameter buffer, the gradient of the last forward_backward,
  // and the parameter groups with their learning-rate scales (LiDAR4D's: the encodings at the
  // step's rate, the flow field and the MLPs scaled by lidar4d.network_lr_scale; one group for
  // the other fields).
  struct ParamGroup {
    size_t offset = 0, count = 0;
    double lr_scale = 1.0;
  };
  struct Trainable {
    cl::Buffer& params;
    const cl::Buffer& grad;
    std::vector<ParamGroup> groups;
  };
  Trainable trainable();
  // Per ray (n_rays × 3, normalised frame) of the last backward that computed them (the batch's
  // with ray_grads, or a term's own FieldPass::backward): gradients of the loss with respect to
  // the ray origins and directions, through every evaluated sample position (early-terminated
  // samples carry none: they are not in the truncated field) and the direction encoding.
  // Importance-sample depths are held fixed, as in the peers' code (they come from a
  // no-gradient coarse pass). Blocking.
  RayGrads read_ray_grads() const;
  // The same ray gradients summed on the device over the rays' world directions
  // (render::PoseGradSums: Σ dL/do and Σ d × dL/dd, the direction encoding's share included),
  // for render::pose_gradient_from_world_sums(): one kernel and one blocking read of 6 floats.
  render::RayGradSums read_ray_grad_sums();
  // read_losses() and read_ray_grad_sums() in one blocking read (the pose-free step with
  // reweighting under the device profile's pose_grad: device): the loss buffer and the sums
  // copied on the device into one buffer. The same values as the two calls.
  struct LossAndRaySums {
    LossReport loss;
    render::RayGradSums sums;
  };
  LossAndRaySums read_losses_and_ray_grad_sums();

  // The list of loss terms (loss_terms.hpp): the config's, then those added here (a step part's:
  // the cross-frame consistency, the flow supervision), run in that order by every following
  // forward_backward. Returns the added term.
  LossTerm& add_loss(std::unique_ptr<LossTerm> term) { return losses_.add(std::move(term)); }
  std::vector<std::string> loss_names() const { return losses_.names(); }
  // The loss terms' values of the last step, in the list's order (blocks until it finished):
  // the loss buffer read once, then each term's own values.
  LossReport read_losses() const;
  // The parameter gradient of the last forward_backward() (every term's). Blocking; for tests.
  std::vector<float> read_gradient() const { return grad_.read_vec<float>(layout_.total()); }
  // The share of the terms' own passes in it (FieldPass; zeros before the first). Blocking; for
  // tests.
  std::vector<float> read_term_gradient() {
    return own_gradient().read_vec<float>(layout_.total());
  }

  // Coarse-to-fine mask of the hash-grid levels (field::barf_level_weights); all ones by default.
  void set_level_weights(const std::vector<float>& w) { encoder_->set_level_weights(w); }
  int levels() const { return encoder_->levels(); }
  // The position encoder (the hash grid, spectral::HybridEncoder when the config's
  // hybrid_encoder() is on, field::Lidar4DEncoder when four_d_encoder() is): read only; the
  // field changes through forward/backward, its parameter groups' steps and the schedules below.
  const field::Encoder& encoder() const { return *encoder_; }
  // SG-NLF's hybrid field (the config's hybrid_encoder()): the fusion weight λ(t) of
  // f_hyb = [f_geo, λ·Ψ] for the following passes (the spectral schedule's set_schedules sets it
  // before every step), and Ψ's parameters (outside the flat buffer; host copies for
  // checkpoints, IoError on a size mismatch; the optimiser that steps them is the spectral loss
  // term's). Each throws sgnlf::Error without the hybrid encoder.
  bool hybrid() const { return hybrid_ != nullptr; }
  void set_fusion_weight(float lambda);
  float fusion_weight() const;
  std::vector<float> read_psi() const;
  void write_psi(const std::vector<float>& params);
  size_t psi_params() const;
  // LiDAR4D's 4D encoder when the config's four_d_encoder() is on, else null.
  field::Lidar4DEncoder* four_d_encoder() { return four_d_; }
  // The time of the following passes for a 4D encoder: dataset frame `frame` of `frames`
  // (field::frame_time); a no-op for the other encoders, which have no time.
  void set_frame(int frame, int frames);
  bool temporal() const { return four_d_ != nullptr; }
  cl::Runtime& runtime() const { return rt_; }

  // Encodings f (N × encoder().width()) at n points (N × 3, normalised box): the per-point
  // features of the pose graph's matching (method.md §4.2). Blocking; chunks of max_rays.
  std::vector<float> encode_points(const std::vector<float>& x, int n);
  // dL/d(depth, return probability, intensity) per ray (n_rays × 3) of the last
  // pass's backward (the batch's: all loss terms added). Blocking; for tests.
  std::vector<float> read_output_gradient() const;

  // Renders rays (n ≤ max_rays; origins/directions n × 3, normalised frame) without jitter:
  // returns n × 3 (depth normalised, return probability, intensity). Blocking. The depth is the
  // expected depth, or the median depth when the config's render.eval_depth is "median" ("mix"
  // is a frame's rule: render_view applies it from depth_stats()).
  std::vector<float> render_rays(const std::vector<float>& origins,
                                 const std::vector<float>& directions, int n);

  // Per ray of the last render_rays() (n × 3): the median depth (normalised), the opacity
  // Σ w and the weight-normalised depth variance (normalised units²): the evaluation's median
  // and "mix" depths (evaluate.hpp). Blocking.
  std::vector<float> depth_stats();

  // The fast renderer (model_fast_render.cpp, pipeline::FastMarch): the same samples as
  // render_rays(), but only those in occupied cells of `grid` are evaluated, front to back
  // until the transmittance falls below cfg.stop_transmittance, and the head only where a
  // sample's weight exceeds cfg.head_weight_threshold. With importance sampling both the
  // coarse and the merged pass march. Same output as render_rays(). With cfg.layout "march"
  // the samples are placed by the grid instead (pipeline::GridMarch: a lattice cfg.refine
  // times finer than the protocol's bins in occupied cells, no importance pass); with
  // refine 1, a full grid and no thresholds that is render_rays() without importance
  // sampling. Blocking.
  std::vector<float> render_rays_fast(const std::vector<float>& origins,
                                      const std::vector<float>& directions, int n,
                                      const render::OccupancyGrid& grid,
                                      const render::FastRenderConfig& cfg);
  // Samples the last render_rays_fast() evaluated with the density MLP, and head rows.
  long fast_evaluated() const { return fast_evaluated_; }
  long fast_head_rows() const { return fast_head_; }
  // Its density rows by kind with layout "march" (zeros with "protocol").
  const GridMarch::Rows& march_rows() const { return march_rows_; }
  // σ logits (σ = exp(h0)) of the field at n points (n × 3, normalised box), at the time
  // set_frame() set for a 4D encoder: what render::OccupancyGrid::build probes. Blocking.
  std::vector<float> density_logits(const std::vector<float>& x, int n);
  // Rows one density_logits() device call takes (the sample buffers' capacity).
  int sample_capacity() const;
  // The LiDAR head at n points (n × 3, normalised box) seen along unit directions (n × 3):
  // n × 2 (return probability, intensity) after the sigmoid, as the renderer weights them
  // (model_bake.cpp; what `sgnlf bake` stores per vertex). Blocking; chunks of max_rays.
  std::vector<float> head_at(const std::vector<float>& x, const std::vector<float>& dirs, int n);
  // The render settings the model was built with (render_view reads the evaluation rules).
  const render::RenderConfig& render_config() const { return cfg_.render; }
  // The renderer's uniform bin width in the normalised frame (the last sample's δ).
  float bin_width() const { return cfg_.render.bin_width(scene_scale_); }

  // With importance sampling the coarse samples' hash encodings are reused in the merged pass
  // (default, exact). Off: the merged pass encodes every sample again (the reference path,
  // for tests and benchmarks); the results are bit-identical. Always off with the 4D encoder:
  // its backward differentiates the state of its last forward (the flowed neighbours), so the
  // rows the backward runs on are encoded last, in one pass.
  void set_reuse_coarse_encodings(bool on) { reuse_coarse_ = on && four_d_ == nullptr; }

  // The registered names of the sampling strategy of training rays and of every other pass
  // (the protocol's): render.training_sampler_name() and render.sampler_name().
  const std::string& training_strategy() const { return training_->name(); }
  const std::string& protocol_strategy() const { return protocol_->name(); }
  // The context of the last sampled pass (forward_backward, a term's FieldPass::render, render_rays):
  // its samples and head rows; valid() false before the first.
  const ForwardContext& last_forward() const { return last_; }

  // Early ray termination (render.stop_transmittance > 0): merged samples behind the point
  // where the coarse pass's transmittance fell below the threshold are not evaluated (zero
  // density). Live samples of the last forward_backward/render call:
  std::vector<int> live_counts() const;  // per ray (blocking read); the pass must be the last
  long live_samples() const { return last_.samples.rows; }
  // Coarse samples evaluated by the last forward_backward/render call (importance sampling or early
  // termination; 0 without): n_rays × n_samples in one pass, fewer with render.coarse_waves > 1.
  long coarse_evaluated() const { return last_.samples.coarse; }
  // Samples the LiDAR head ran on in the last call with render.head_weight_threshold > 0.
  long head_rows() const { return last_.head == HeadRows::Band ? last_.head_rows : 0; }

 private:
  // Starts a pass that overwrites the activations (any earlier context is stale); returns its
  // number.
  uint64_t begin_pass() { return ++pass_; }
  // A new sampled pass of n_rays rays from o_/d_ (and target_) with sampler `s`.
  SampleSet sample(Sampler& s, int n_rays, bool jitter, uint64_t seed, uint32_t step);
  // The field and renderer on the samples of `s` (at t_/x_, the live rows when compacted):
  // fills h0_, head_out_, out_, weights_; returns the backward's context.
  ForwardContext forward(const SampleSet& s);
  // The head on the band of samples with weight above render.head_weight_threshold (after the
  // density on the live rows): fills h0_, weights_ and head_out_ (full layout); returns its rows.
  long head_band(int n_rays, int M);
  // The backward of the forward `ctx` (throws when its activations were overwritten) from
  // grad_out_ into `grad` (every slice overwritten), and the ray gradients when `ray_grads`.
  // `pass`: the loss terms' per-sample gradients join the renderer's (null: none, a term's own
  // pass).
  void backward(const ForwardContext& ctx, cl::Buffer& grad, bool ray_grads, LossPass* pass);
  // A term's own pass (loss_term.hpp's FieldPass, model_field_pass.cpp) reaches the field here,
  // a term's own parameter group (OwnGroupStep) too.
  friend class FieldPass;
  friend class OwnGroupStep;
  spectral::HybridEncoder& hybrid_or_throw(const char* who) const;

  cl::Runtime& rt_;
  TrainConfig cfg_;
  int max_rays_;
  field::ParamLayout layout_;
  spectral::HybridEncoder* hybrid_ = nullptr;  // encoder_ when it is the hybrid one (set first)
  field::Lidar4DEncoder* four_d_ = nullptr;    // encoder_ when it is LiDAR4D's (set first)
  float scene_scale_ = 1.0f;
  // Flow supervision (FieldPass::flow): points, times, flow and its gradient (capacity
  // flow_cap_ points); the times of the device variant, written without blocking.
  cl::Buffer fx_, ft_, fflow_, fdflow_;
  int flow_cap_ = 0;
  cl::StagedUpload up_ft_;
  // The flow's buffers for n points and the second gradient readied for its slice.
  field::SceneFlow& begin_flow(int n, const char* who);
  // The second gradient (the terms' own passes: FieldPass), allocated on first use; the model
  // adds it to grad_ at the end of the step whose term wrote it. grad_own_ holds only the flow
  // slice's gradient (zero elsewhere) unless a rendered rays' backward wrote every slice since
  // it was last cleared (own_full_).
  cl::Buffer& own_gradient();
  cl::Buffer grad_own_;
  cl::Kernel add_k_;
  bool own_full_ = false;
  std::unique_ptr<field::Encoder> encoder_;
  field::Mlp density_, head_;
  field::DirEncoding dirs_;
  render::RaySampler sampler_;
  render::VolumeRenderer renderer_;
  render::RangeLoss loss_;
  render::RayGradReducer ray_grad_;
  // Glue between the field and render launchers: σ logit column of the density output ↔ h0
  // (field/columns.cl), the clamp of sample positions to the scene box (render/sample.cl).
  cl::Kernel col_get_, col_set_, clamp_;
  bool reuse_coarse_ = true;
  // The pass counter (begin_pass), the last sampled pass's context.
  uint64_t pass_ = 0;
  ForwardContext last_;
  size_t off_grid_, off_density_, off_head_;
  field::MlpContext density_ctx_, head_ctx_;
  cl::Buffer params_, grad_;
  cl::Buffer o_, d_, target_, t_c_, x_c_, w_c_, enc_c_, t_, x_, enc_, dens_, h0_, dir_enc_,
      head_out_, out_, weights_, grad_out_, terms_, loss_buf_, g_h0_, g_head_, g_dens_, g_enc_,
      g_dir_enc_;
  // The training batch's host copies (origins, directions, targets), written into o_, d_ and
  // target_ without blocking and kept until the queue has read them.
  cl::StagedUpload up_o_, up_d_, up_target_;
  // Pose-free methods: dL/dx per evaluated sample, per-ray dL/do, dL/dd, and the direction
  // encoding's share of dL/dd.
  cl::Buffer g_x_, g_o_, g_d_, g_dir_;
  int grad_rays_ = 0;
  // The launcher of the ray gradients' sums, made on first use.
  std::unique_ptr<render::PoseGradSums> pose_sums_;
  cl::Buffer loss_and_sums_;  // read_losses_and_ray_grad_sums(): the loss buffer, then the sums
  // The optional sampling modes' launchers the forward shares with the samplers, null when the
  // config does not use the mode: importance sampling (n_importance > 0), early termination
  // (stop_transmittance > 0), and with it the head band (head_weight_threshold > 0).
  std::unique_ptr<EncodingReuse> reuse_;
  std::unique_ptr<SampleCompaction> live_;
  std::unique_ptr<HeadBand> band_;
  // Weight carving (render.weights.carve > 0), null when off.
  std::unique_ptr<render::WeightCarving> carve_;
  // The samplers (sampler.hpp), made by name: the protocol's (render.sampler_name()), and the
  // training rays' (render.training_sampler_name(): training_sampler_ where it is another
  // strategy, else the protocol's); the loss terms (loss_terms.hpp).
  std::unique_ptr<Sampler> protocol_, training_sampler_;
  Sampler* training_ = nullptr;
  LossList losses_;
  // depth_stats(): the last render_rays()'s rays and samples, and its outputs.
  int stats_rays_ = 0, stats_samples_ = 0;
  cl::Buffer stats_median_, stats_spread_;
  int samples_cap_ = 0;  // sample rows per ray the buffers hold
  // The fast renderer's marching, made on its first use with its config.
  std::unique_ptr<FastMarch> fast_;
  std::unique_ptr<GridMarch> march_;
  render::FastRenderConfig fast_cfg_;
  long fast_evaluated_ = 0, fast_head_ = 0;
  GridMarch::Rows march_rows_;
};

// Capacity (rays) a model needs for training and chunked rendering under `c`.
inline int model_capacity(const TrainConfig& c) {
  return std::max(c.schedule.rays_per_batch, c.schedule.render_chunk_rays);
}

}  // namespace sgnlf::pipeline
