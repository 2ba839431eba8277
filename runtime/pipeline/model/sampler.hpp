// The sampler interface of LidarNerfModel (model.hpp): one call places the samples of a pass
// along its rays and returns the SampleSet the field's forward runs on (sample_set.hpp). Its
// strategies are the protocol's sampling modes and the training sampler by the return:
// uniform; importance with the coarse encodings reused (EncodingReuse); early termination's
// compaction of the live samples (SampleCompaction), its coarse pass in waves (CoarseWaves);
// samples by the measured return (render::SurfaceSampler). The head band is the forward's
// (forward_context.hpp: HeadRows), not a sampler's. The strategies use the model's launchers
// and buffers (SamplerParts, SampleBuffers) and its field's density-only pass (SamplerField);
// every call only enqueues, but for the host syncs of early termination (one per pass, one per
// coarse wave but the last).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>

#include "cl/runtime.hpp"
#include "field/encoder.hpp"
#include "pipeline/model/coarse_waves.hpp"
#include "pipeline/model/encoding_reuse.hpp"
#include "pipeline/model/sample_compaction.hpp"
#include "pipeline/model/sample_set.hpp"
#include "render/ray_sampler.hpp"
#include "render/render_config.hpp"
#include "render/surface_sampler.hpp"

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
// per-ray count), and the pass's rays (n_rays × 3) and targets (n_rays × 3, for Surface).
struct SampleBuffers {
  const cl::Buffer &origins, &directions, &targets;
  cl::Buffer &t_c, &x_c, &w_c, &enc_c;  // the coarse pass: n_rays × n_samples
  cl::Buffer &t, &x, &enc, &h0;         // the full layout
};

// The model's launchers a strategy uses; null where the config lacks the mode.
struct SamplerParts {
  render::RaySampler& rays;
  EncodingReuse* reuse = nullptr;            // n_importance > 0
  SampleCompaction* live = nullptr;          // stop_transmittance > 0
  CoarseWaves* waves = nullptr;              // coarse_waves > 1 with stop_transmittance
  render::SurfaceSampler* surface = nullptr; // surface_band_samples > 0
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

class Sampler {
 public:
  virtual ~Sampler() = default;
  virtual SampleStrategy strategy() const = 0;
  virtual SampleSet sample(const SampleRequest& r) = 0;
};

// The protocol's strategy of a render config: Terminated with stop_transmittance > 0, else
// Importance with n_importance > 0, else Uniform.
SampleStrategy protocol_strategy(const render::RenderConfig& rc);
// The sampler of strategy `s` (its launchers must be in `parts`: throws Error naming the one
// missing). The buffers, parts and field must outlive it.
std::unique_ptr<Sampler> make_sampler(SampleStrategy s, const render::RenderConfig& rc,
                                      const SamplerParts& parts, const SampleBuffers& buffers,
                                      const SamplerField& field);

}  // namespace sgnlf::pipeline
