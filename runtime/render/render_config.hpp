// Configuration of LiDAR ray sampling, volume rendering and the range loss (method.md §0,
// §1). Lengths are in metres here; the render classes take the scene scale s (protocol §2)
// and work in the normalised frame (near·s, far·s, ranges·s).
#pragma once
#include <cstdint>
#include <string>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::render {

struct RangeLossWeights {
  float depth = 1000.0f;    // α_d: L1 of depth, masked by the GT return
  float ret = 1.0f;         // α_r: MSE of return probability vs the GT label
  float intensity = 10.0f;  // α_i: MSE of intensity, masked
  float grad = 100.0f;      // range-image gradient loss on patches (LiDAR-NeRF)
  // Weight carving (NeuRAD's L_w, render/weight_carving.hpp): mean over rays with a return of
  // sum w_i^2 over the samples farther than the surface band's half-width from the return.
  // 0: off.
  float carve = 0.0f;
  // The keys and ranges (core/config_fields.hpp); errors name "<render>.weights".
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("depth", s.depth, 0.0f, 1e9f);
    v("ret", s.ret, 0.0f, 1e9f);
    v("intensity", s.intensity, 0.0f, 1e9f);
    v("grad", s.grad, 0.0f, 1e9f);
    v("carve", s.carve, 0.0f, 1e9f, config::omit_when(0.0f));
  }
};

struct RenderConfig {
  float near_m = 1.0f;
  float far_m = 81.0f;
  int n_samples = 64;    // uniform samples per ray (paper: 768)
  int n_importance = 0;  // extra importance samples (LiDAR-NeRF: 64); 0 = off
  bool jitter = true;    // stratified jitter in training; midpoints when false
  // Sampling when a trained run is rendered (eval, render, the harness): 0 / -1 keep
  // n_samples / n_importance. The checkpoint does not depend on it; a preset trained with few
  // samples may render its test views with more (closer to the paper's 768).
  int eval_samples = 0;
  int eval_importance = -1;
  // Depth of a rendered (evaluated) ray: "expected" = sum w_i t_i (method.md §0, what every
  // method here trains with and the tables report) or "median" = the t where the accumulated
  // weight reaches 1/2 (it cannot blend a foreground edge with the background) or "mix"
  // (GS-LiDAR's: the median where a ray's depth variance exceeds 10x the frame's median
  // variance, the expected depth elsewhere: view_rules.hpp; the fast renderer, which keeps no
  // variance, renders the median for it).
  // Training always uses the expected depth.
  std::string eval_depth = "expected";
  // "mix"'s factor on the frame's median depth variance (GS-LiDAR's 10).
  float eval_mix_factor = 10.0f;
  // A rendered return at a range the sensor cannot report (Sensor::in_range) becomes a drop, as
  // the loaders treat such points in the observed images (view_rules.hpp). Evaluation only.
  bool eval_drop_out_of_range = false;
  // Early ray termination (instant-ngp / torch-ngp's transmittance threshold): samples behind
  // the point where a density-only pass's transmittance drops below this (plus one coarse bin)
  // are not evaluated; their weight is below it. With importance sampling that pass is the
  // coarse pass; with uniform samples only (GeoNLF, SG-NLF) it is a density-only pass over the
  // same samples, whose encodings the training pass reuses. 0: off, every sample evaluated
  // (exact). Applies to training and rendering.
  float stop_transmittance = 0.0f;
  // Early termination of the coarse pass too: the uniform samples are evaluated in
  // this many waves front to back, and a ray whose coarse transmittance fell below
  // stop_transmittance (plus the termination's margin bin) takes no part in later waves. The
  // samples it skips lie behind the termination point: the merged samples' live prefix, its
  // encodings and the renderer's output are those of the one-wave pass, the importance pdf
  // loses at most the weight behind termination (< stop_transmittance). 1: every coarse sample
  // evaluated in one pass (the published behaviour). Needs stop_transmittance.
  int coarse_waves = 1;
  // The LiDAR head only where a sample's weight exceeds this (LiDAR-NeRF's released code uses
  // 1e-4): per ray, the band from the first to the last live sample above it; the head
  // outputs of the other samples are taken as zero (their share of the return probability and
  // intensity is below this weight each; depth is untouched). 0: the head runs on every live
  // sample. Needs stop_transmittance (it works on the live samples).
  float head_weight_threshold = 0.0f;
  // Training samples placed by the measured return (render/surface_sampler.hpp; the peers
  // sample uniformly): per training ray with a return at range r, surface_free_samples
  // stratified in [near, r - w], surface_band_samples in [r - w, r + w] and
  // surface_behind_samples behind it: all but the last in [r + w, r + w + surface_behind_m],
  // the last one over the rest of the ray up to far (the samples reach far, as the protocol's
  // do); rays without a return get the same count stratified over [near, far]. The band's half-width w goes log-linearly from
  // surface_band_start_m to surface_band_end_m over the first surface_anneal_steps steps.
  // Training only (test rays have no return: they are rendered with n_samples / eval_samples).
  // 0 band samples: off.
  int surface_band_samples = 0;
  int surface_free_samples = 16;
  int surface_behind_samples = 4;
  float surface_band_start_m = 1.0f;
  float surface_band_end_m = 0.2f;
  int surface_anneal_steps = 2000;
  float surface_behind_m = 2.0f;
  // The sampling strategies by their registered names (pipeline/model/sampler.hpp): `sampler`
  // places the samples of every pass (training, rendering, evaluation), `training_sampler`
  // those of training rays. Absent (empty): the name the keys above imply, sampler_name() and
  // training_sampler_name(), so the configs written before these keys keep their JSON and
  // hash. The model checks a name against the registry (an unknown one is a ConfigError
  // naming the key).
  std::string sampler;
  std::string training_sampler;
  RangeLossWeights weights;
  // Gradient loss on patch batches (LiDAR-NeRF: 2 × 8 patches, L1, GT steps ≥ 1 cm ignored).
  int patch_rows = 2;
  int patch_cols = 8;
  bool grad_l1 = true;        // L1 of the difference error; false: squared error
  float grad_clip_m = 0.01f;  // pairs whose GT depth step is ≥ this are ignored

  // The keys and ranges (core/config_fields.hpp), in the order validate() names the first
  // value outside its range. Keys added after results were committed are written only when
  // not their old value, so configs without them keep their JSON and hash. coarse_waves'
  // range [1, n_samples] and the rules between keys are validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("near_m", s.near_m, 0.0f, 1e4f);
    v("far_m", s.far_m, 0.0f, 1e5f);
    v("n_samples", s.n_samples, 1, 1 << 16);
    v("n_importance", s.n_importance, 0, 1 << 16);
    v("jitter", s.jitter);
    v("eval_samples", s.eval_samples, 0, 1 << 16, config::omit_when(0));
    v("eval_importance", s.eval_importance, -1, 1 << 16, config::omit_when(-1));
    v("eval_depth", s.eval_depth, config::omit_when<std::string>("expected"));
    v("eval_mix_factor", s.eval_mix_factor, 1e-3f, 1e6f, config::omit_when(10.0f));
    v("eval_drop_out_of_range", s.eval_drop_out_of_range, config::omit_when(false));
    v("stop_transmittance", s.stop_transmittance, 0.0f, 0.5f, config::omit_when(0.0f));
    v("coarse_waves", s.coarse_waves, config::omit_when(1));
    v("head_weight_threshold", s.head_weight_threshold, 0.0f, 0.1f, config::omit_when(0.0f));
    v("surface_band_samples", s.surface_band_samples, 0, 1 << 12, config::omit_when(0));
    v("surface_free_samples", s.surface_free_samples, 1, 1 << 12, config::omit_when(16));
    v("surface_behind_samples", s.surface_behind_samples, 1, 1 << 12, config::omit_when(4));
    v("surface_band_start_m", s.surface_band_start_m, 1e-3f, 100.0f, config::omit_when(1.0f));
    v("surface_band_end_m", s.surface_band_end_m, 1e-3f, 100.0f, config::omit_when(0.2f));
    v("surface_anneal_steps", s.surface_anneal_steps, 0, 1 << 28, config::omit_when(2000));
    v("surface_behind_m", s.surface_behind_m, 0.0f, 100.0f, config::omit_when(2.0f));
    v("sampler", s.sampler, config::omit_when<std::string>(""));
    v("training_sampler", s.training_sampler, config::omit_when<std::string>(""));
    v.section("weights", s.weights);
    v("patch_rows", s.patch_rows, 1, 256);
    v("patch_cols", s.patch_cols, 1, 256);
    v("grad_l1", s.grad_l1);
    v("grad_clip_m", s.grad_clip_m, 0.0f, 1e5f);
  }

  // Dataset presets of the loss weights: "kitti360" (1000, 1, 10), "nuscenes" (1000, 4.5, 100).
  static RenderConfig preset(const std::string& dataset);
  void validate(const std::string& where = "render") const;
  // Reads the keys of this struct (all optional, unknown keys rejected) and validates.
  static RenderConfig from_json(const Json& j, const std::string& where);
  static RenderConfig from_json(const Json& j, const std::string& where, RenderConfig defaults);
  // eval_samples / eval_importance / eval_depth / stop_transmittance / coarse_waves /
  // head_weight_threshold / surface_* / sampler / training_sampler appear only when set, so
  // configs without them keep their JSON and hash (run folders and baselines written before
  // they existed still load).
  Json to_json() const;
  // The strategy of every pass: `sampler` when given, else "terminated" with
  // stop_transmittance > 0, "importance" with n_importance > 0, "uniform" otherwise (the
  // protocol's). Resolved where the model is made, from the keys as they are then (evaluation
  // may set n_samples / n_importance from eval_samples / eval_importance).
  std::string sampler_name() const;
  // The strategy of training rays: `training_sampler` when given, else "surface" with
  // surface_band_samples > 0, else sampler_name().
  std::string training_sampler_name() const;
  bool surface_sampling() const { return surface_band_samples > 0; }
  int surface_samples() const {
    return surface_free_samples + surface_band_samples + surface_behind_samples;
  }
  // The surface band's half-width (metres) at training step `step`.
  float surface_band_m(long step) const;
  // Uniform bin width in normalised units: also the last sample's δ (see kernels/render/volume.cl).
  float bin_width(float scene_scale) const {
    return (far_m - near_m) * scene_scale / float(n_samples);
  }
};

}  // namespace sgnlf::render
