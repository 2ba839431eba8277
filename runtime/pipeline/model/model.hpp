// The LiDAR-NeRF model on the device (method.md §0–1): position encoder (field::Encoder: the
// hash grid, or SG-NLF's hybrid [f_geo, λ·Ψ]) → density MLP (σ logit + 15 geometric features)
// → [geo, direction encoding] → LiDAR head → volume rendering, the training losses, the
// backward chain and Adam over one flat parameter buffer.
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
// - the loss terms (loss_terms.hpp: range, patch gradient, Chamfer, weight carving) each add
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
#include "field/adam.hpp"
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

// Device-side state that checkpoints hold (host copies).
struct ModelState {
  std::vector<float> params, adam_m, adam_v;
  int64_t adam_step = 0;
};

class LidarNerfModel {
 public:
  // `max_rays`: the largest ray count of one call (training batch or render chunk).
  LidarNerfModel(cl::Runtime& rt, const TrainConfig& c, float scene_scale, int max_rays);

  size_t n_params() const { return layout_.total(); }
  const field::ParamLayout& layout() const { return layout_; }
  // Deterministic initialisation from `seed` (hash grid ±1e-4, MLP fan-in uniform).
  void init_params(uint64_t seed);

  // One training step in two parts, composed by the trainer: forward_backward enqueues the
  // sampling, forward, loss and backward of one batch into the gradient buffer (and, with
  // `ray_grads`, dL/d(origin) and dL/d(direction) of every ray for the pose-free methods, read
  // with read_ray_grads()); update() enqueues the Adam step of every parameter group. No wait.
  void forward_backward(const RayBatch& b, uint64_t seed, long step, bool ray_grads = false);
  void update(float lr);
  // Both parts (the ground-truth-pose methods' step).
  void train_step(const RayBatch& b, uint64_t seed, long step, float lr) {
    forward_backward(b, seed, step);
    update(lr);
  }
  // Per ray (n_rays × 3 each, normalised frame) of the last forward_backward(..., true):
  // gradients of the loss with respect to the ray origins and directions, through every
  // evaluated sample position (early-terminated samples carry none: they are not in the
  // truncated field) and the direction encoding. Importance-sample depths are held fixed, as
  // in the peers' code (they come from a no-gradient coarse pass). Blocking.
  struct RayGrads {
    std::vector<float> origin, direction;
  };
  RayGrads read_ray_grads() const;
  // The device profile's pose_grad when the model was made: device = the pose-free step takes
  // read_ray_grad_sums() instead of read_ray_grads().
  bool pose_grad_on_device() const { return pose_grad_device_; }
  // The same ray gradients summed on the device over the rays' world directions
  // (render::PoseGradSums: Σ dL/do and Σ d × dL/dd, the direction encoding's share included),
  // for render::pose_gradient_from_world_sums(): one kernel and one blocking read of 6 floats.
  render::RayGradSums read_ray_grad_sums();
  // read_loss() and read_ray_grad_sums() in one blocking read (the pose-free step with
  // reweighting: its only read of the step) when the profile's loss_reduce is device: the loss
  // buffer and the sums copied on the device into one buffer. The same values as the two calls;
  // otherwise it is the two calls.
  struct LossAndRaySums {
    render::LossValues loss;
    render::RayGradSums sums;
  };
  LossAndRaySums read_loss_and_ray_grad_sums();

  // An externally given per-ray output gradient through the same backward chain (SG-NLF's
  // adversarial consistency term, method.md §4.3–4.4): forward_rays() is the training-mode
  // forward of the protocol's sampling (jitter per the config from (seed, step)) that keeps
  // its ForwardContext and returns n × 3 (depth normalised, return probability, intensity);
  // backward_external() takes dL/d(depth, return probability, intensity) per ray (n × 3, the
  // caller's weight already applied) through that context's backward into a gradient buffer
  // of its own, and, with `ray_grads`, the ray gradients read_ray_grads() returns. It throws
  // when another pass (a training step, a render, an encoding) ran since forward_rays(): the
  // activations are then that pass's; and it differentiates a forward once.
  //
  // Combination: the external gradient is ACCUMULATED into the gradient of the next update(),
  // which adds it to the gradient forward_backward() wrote before the one Adam step (so the
  // external term of a step is computed before that step's forward_backward, whose gradient
  // buffer it does not touch). method.md §4.4 defines one total loss L = L_range + … +
  // λ_con·L_con: one Adam step on the sum of the gradients is that loss's step, and λ_con
  // keeps its meaning as a relative weight. Its own Adam step would not: Adam divides by the
  // running RMS, so a separate step moves the parameters by ≈ lr whatever λ_con is, and it
  // would advance Adam's step count (bias correction, lr schedule) twice per iteration.
  // Without a pending external gradient update() is exactly what it was.
  std::vector<float> forward_rays(const std::vector<float>& origins,
                                  const std::vector<float>& directions, int n, uint64_t seed,
                                  long step);
  void backward_external(const std::vector<float>& grad_out, bool ray_grads);
  bool external_gradient_pending() const { return ext_pending_; }
  // The parameter gradient of the last update() (range loss + any external term), or of the
  // last forward_backward() before its update. Blocking; for tests.
  std::vector<float> read_gradient() const { return grad_.read_vec<float>(layout_.total()); }

  // Coarse-to-fine mask of the hash-grid levels (field::barf_level_weights); all ones by default.
  void set_level_weights(const std::vector<float>& w) { encoder_->set_level_weights(w); }
  int levels() const { return encoder_->levels(); }
  // The position encoder (the hash grid, or spectral::HybridEncoder when the config's
  // hybrid_encoder() is on: the spectral schedule reaches Ψ through it).
  field::Encoder& encoder() { return *encoder_; }
  // The same encoder as SG-NLF's hybrid one when the config's hybrid_encoder() is on, else null.
  spectral::HybridEncoder* hybrid_encoder() { return hybrid_; }
  // LiDAR4D's 4D encoder when the config's four_d_encoder() is on, else null.
  field::Lidar4DEncoder* four_d_encoder() { return four_d_; }
  // The field's optimiser (its settings: the config's optim.adam).
  const field::Adam& optimizer() const { return *adam_; }
  // The time of the following passes for a 4D encoder: dataset frame `frame` of `frames`
  // (field::frame_time); a no-op for the other encoders, which have no time.
  void set_frame(int frame, int frames);
  bool temporal() const { return four_d_ != nullptr; }
  // LiDAR4D's flow supervision (model_four_d.cpp): the flow field at n points x (n × 3,
  // normalised box) at the time set_frame() set; `loss` maps the flow (n × 6: forward, backward)
  // to its loss and writes dL/dflow (n × 6). The flow field's parameter gradient is pending
  // like an external one (backward_external) and joins the next update(). Returns the loss.
  // Blocking (one read of the flow). Needs the 4D encoder.
  using FlowLoss = std::function<double(const std::vector<float>& flow, std::vector<float>& d_flow)>;
  double flow_supervision(const std::vector<float>& x, int n, const FlowLoss& loss);
  // The same with the points on the device (x: n × 3, unchanged until the next update()) and
  // the loss on the device: `loss` enqueues dL/dflow (d_flow, n × 6) from the flow (n × 6).
  // The time is written without blocking; nothing is read back (the device profile's
  // chamfer: device, FlowSupervisionStep).
  using DeviceFlowLoss = std::function<void(const cl::Buffer& flow, cl::Buffer& d_flow)>;
  void flow_supervision_device(const cl::Buffer& x, int n, const DeviceFlowLoss& loss);
  // The device profile's chamfer is device (when the model was made): LiDAR4D's Chamfer term
  // and flow supervision run on the device, their values read only when asked.
  bool chamfer_on_device() const { return chamfer_device_; }
  cl::Runtime& runtime() const { return rt_; }
  // LiDAR4D's Chamfer term (config lidar4d.chamfer_weight) of the last forward_backward, 0 when
  // off; read back with the step (the term needs the batch's depths on the host), or (chamfer:
  // device) read from the device when asked.
  double last_chamfer() const { return loss_value("chamfer"); }
  // The training loss terms in the order they run (loss_terms.hpp), and the value of the named
  // one in the last forward_backward (0 when the config has no such term). Blocking.
  std::vector<std::string> loss_names() const;
  double loss_value(const std::string& name) const;

  // Encodings f (N × encoder().width()) at n points (N × 3, normalised box): the per-point
  // features of the pose graph's matching (method.md §4.2). Blocking; chunks of max_rays.
  std::vector<float> encode_points(const std::vector<float>& x, int n);
  // The loss values of the last train_step, each term's fields (blocks until it finished).
  render::LossValues read_loss() const;
  // dL/d(depth, return probability, intensity) per ray (n_rays × 3) of the last
  // forward_backward, all loss terms added (or the external one of backward_external).
  // Blocking; for tests.
  std::vector<float> read_output_gradient() const;

  // Renders rays (n ≤ max_rays; origins/directions n × 3, normalised frame) without jitter:
  // returns n × 3 (depth normalised, return probability, intensity). Blocking. The depth is the
  // expected depth, or the median depth when the config's render.eval_depth is "median".
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
  // The context of the last sampled pass (train_step, forward_rays, render_rays): its samples
  // and head rows; valid() false before the first.
  const ForwardContext& last_forward() const { return last_; }

  // Early ray termination (render.stop_transmittance > 0): merged samples behind the point
  // where the coarse pass's transmittance fell below the threshold are not evaluated (zero
  // density). Live samples of the last train_step/render call:
  std::vector<int> live_counts() const;  // per ray (blocking read); the pass must be the last
  long live_samples() const { return last_.samples.rows; }
  // Coarse samples evaluated by the last train_step/render call (importance sampling or early
  // termination; 0 without): n_rays × n_samples in one pass, fewer with render.coarse_waves > 1.
  long coarse_evaluated() const { return last_.samples.coarse; }
  // Samples the LiDAR head ran on in the last call with render.head_weight_threshold > 0.
  long head_rows() const { return last_.head == HeadRows::Band ? last_.head_rows : 0; }

  ModelState state() const;
  void set_state(const ModelState& s);

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
  // `pass`: the loss terms' per-sample gradients join the renderer's (null: none, the external
  // gradient's backward).
  void backward(const ForwardContext& ctx, cl::Buffer& grad, bool ray_grads, LossPass* pass);

  cl::Runtime& rt_;
  TrainConfig cfg_;
  int max_rays_;
  field::ParamLayout layout_;
  spectral::HybridEncoder* hybrid_ = nullptr;  // encoder_ when it is the hybrid one (set first)
  field::Lidar4DEncoder* four_d_ = nullptr;    // encoder_ when it is LiDAR4D's (set first)
  float scene_scale_ = 1.0f;
  // Flow supervision: points, times, flow and its gradient (capacity flow_cap_ points).
  cl::Buffer fx_, ft_, fflow_, fdflow_;
  int flow_cap_ = 0;
  cl::StagedUpload up_ft_;  // flow_supervision_device(): the times, written without blocking
  bool chamfer_device_ = false;
  // The flow supervision's buffers for n points and its pending gradient's slice, readied.
  field::SceneFlow& begin_flow(int n, const char* who);
  // grad_ext_ holds only the flow slice's gradient (zero elsewhere) unless backward_external
  // wrote every slice since it was last cleared.
  bool ext_full_ = false;
  std::unique_ptr<field::Encoder> encoder_;
  field::Mlp density_, head_;
  field::DirEncoding dirs_;
  std::unique_ptr<field::Adam> adam_;
  render::RaySampler sampler_;
  render::VolumeRenderer renderer_;
  render::RangeLoss loss_;
  render::RayGradReducer ray_grad_;
  // Glue between the field and render launchers: σ logit column of the density output ↔ h0
  // (field/columns.cl), the clamp of sample positions to the scene box (render/sample.cl).
  cl::Kernel col_get_, col_set_, clamp_;
  bool reuse_coarse_ = true;
  // The pass counter (begin_pass), the last sampled pass's context, forward_rays()'s context
  // (invalid once differentiated).
  uint64_t pass_ = 0;
  ForwardContext last_, rays_ctx_;
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
  // The profile's pose_grad: device; the launcher of the sums, made on first use.
  bool pose_grad_device_ = false;
  std::unique_ptr<render::PoseGradSums> pose_sums_;
  cl::Buffer loss_and_sums_;  // read_loss_and_ray_grad_sums(): the loss buffer, then the sums
  // The profile's loss_reduce: device (read_loss() reads the loss buffer once).
  bool loss_device_ = false;
  // External gradient (backward_external): its parameter gradient, pending until update(),
  // when field/accumulate.cl adds it to grad_.
  cl::Buffer grad_ext_;
  cl::Kernel add_k_;
  bool ext_pending_ = false;
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
  // strategy, else the protocol's); the training loss terms (loss_terms.hpp).
  std::unique_ptr<Sampler> protocol_, training_sampler_;
  Sampler* training_ = nullptr;
  std::vector<std::unique_ptr<LossTerm>> losses_;
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
