// The sampler interface of LidarNerfModel (model.hpp): one call places the samples of a pass
// along its rays and returns the SampleSet the field's forward runs on (sample_set.hpp).
//
// A strategy is one class in one file of samplers/, registered under its name (SamplerKind);
// the config names it (render.sampler for every pass, render.training_sampler for training
// rays; absent, the name the numeric keys imply: RenderConfig::sampler_name()), and the model
// makes it by that name. The built-in ones: uniform; importance with the coarse encodings
// reused (EncodingReuse); terminated, early termination's compaction of the live samples
// (SampleCompaction) with its coarse pass in waves (CoarseWaves); surface, samples by the
// measured return (render::SurfaceSampler). A strategy builds the launchers only it uses from
// its SamplerContext; the model's buffers, its field's density-only pass and the launchers its
// forward shares (SamplerParts) come in the context. The head band is the forward's
// (forward_context.hpp: HeadRows), not a sampler's. Every call only enqueues, but for the host
// syncs of early termination (one per pass, one per coarse wave but the last).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "field/encoder.hpp"
#include "pipeline/model/coarse_waves.hpp"
#include "pipeline/model/encoding_reuse.hpp"
#include "pipeline/model/sample_compaction.hpp"
#include "pipeline/model/sample_set.hpp"
#include "render/ray_sampler.hpp"
#include "render/render_config.hpp"

namespace sgnlf::pipeline {

struct SampleRequest {
  int n_rays = 0;
  bool jitter = false;  // stratified jitter keyed by (seed, step); bin midpoints when false
  uint64_t seed = 0;
  uint32_t step = 0;
  // The coarse pass's encodings may stand for the merged / live rows' (exact; off for the 4D
  // encoder and for the reference path, LidarNerfModel::set_reuse_coarse_encodings).
  bool reuse_encodings = true;
};

// The model's sample buffers a strategy writes (capacity: max_rays rays of the largest
// per-ray count of its samplers, SamplerKind::per_ray), and the pass's rays (n_rays × 3) and
// targets (n_rays × 3: range, intensity, label; training rays only).
struct SampleBuffers {
  const cl::Buffer &origins, &directions, &targets;
  cl::Buffer &t_c, &x_c, &w_c, &enc_c;  // the coarse pass: n_rays × n_samples
  cl::Buffer &t, &x, &enc, &h0;         // the full layout
};

// The launchers the model's forward, backward or fast renderer use as well, so the model owns
// them; null where the config lacks the mode. A new strategy adds nothing here: it builds its
// own launchers from the context.
struct SamplerParts {
  render::RaySampler& rays;
  EncodingReuse* reuse = nullptr;    // n_importance > 0 (the fast renderer's too)
  SampleCompaction* live = nullptr;  // stop_transmittance > 0 (the forward runs on its rows)
};

// The field's parts the density-only coarse pass runs on.
struct SamplerField {
  field::Encoder& encoder;
  const cl::Buffer& params;
  size_t grid_offset;
  // Encodes `rows` positions x into enc, runs the density MLP on them; returns its output.
  CoarseWaves::Field density;
  // Column 0 (the σ logit) of `rows` density-output rows into h0.
  std::function<void(const cl::Buffer& dens, int rows, cl::Buffer& h0)> sigma;
  // The renderer's weights w of n_rays × S samples at t with σ logits h0.
  std::function<void(const cl::Buffer& t, const cl::Buffer& h0, int n_rays, int S, cl::Buffer& w)>
      weights;
  // Clamps `rows` positions x to the scene box.
  std::function<void(cl::Buffer& x, int rows)> clamp;
};

// What a strategy is made from. The referenced objects outlive the sampler.
struct SamplerContext {
  cl::Runtime& rt;
  const render::RenderConfig& render;  // the model's (n_samples, n_importance, surface_*, ...)
  float scene_scale;
  int max_rays;
  int encoder_width;  // floats per encoded sample
  SamplerParts parts;
  SampleBuffers buffers;
  SamplerField field;
};

class Sampler {
 public:
  virtual ~Sampler() = default;
  // Places the samples of r.n_rays rays (the model records the strategy's name in the set).
  virtual SampleSet sample(const SampleRequest& r) = 0;
  const std::string& name() const { return name_; }

 private:
  friend std::unique_ptr<Sampler> make_sampler(const std::string&, const std::string&,
                                               const SamplerContext&);
  std::string name_;
};

// A registered strategy.
struct SamplerKind {
  std::string name;
  // Samples per ray of its full layout under a render config (the model's sample buffers hold
  // max_rays × the largest of its samplers').
  int (*per_ray)(const render::RenderConfig&) = nullptr;
  // Throws ConfigError (naming `key`, the config key that chose it) where the render config
  // lacks what the strategy needs; may be null.
  void (*check)(const render::RenderConfig&, const std::string& key) = nullptr;
  std::unique_ptr<Sampler> (*make)(const SamplerContext&) = nullptr;
};

// Adds a strategy (throws Error on a name already registered). The built-in ones are listed in
// sampler_registry.cpp; a strategy outside the library (a test's) registers itself with a
// static SamplerRegistration.
void register_sampler(const SamplerKind& kind);
// The strategy registered as `name`, after its check; ConfigError naming `key` (e.g.
// "render.sampler") for a name not registered, listing those that are.
const SamplerKind& find_sampler(const std::string& name, const std::string& key,
                                const render::RenderConfig& rc);
std::vector<std::string> sampler_names();  // sorted
// The sampler registered as `name` (find_sampler's errors), made from `context`.
std::unique_ptr<Sampler> make_sampler(const std::string& name, const std::string& key,
                                      const SamplerContext& context);

struct SamplerRegistration {
  explicit SamplerRegistration(const SamplerKind& kind) { register_sampler(kind); }
};

}  // namespace sgnlf::pipeline
