// "terminated": early ray termination (render.stop_transmittance > 0). The coarse pass (in
// render.coarse_waves waves, CoarseWaves) finds each ray's termination point, and the field
// runs on the live prefix (SampleCompaction) of the uniform (n_importance = 0) or merged
// samples.
#include <algorithm>

#include "pipeline/model/samplers/sampler_base.hpp"

namespace sgnlf::pipeline::samplers {
namespace {

class TerminatedSampler final : public SamplerBase {
 public:
  explicit TerminatedSampler(const SamplerContext& c) : SamplerBase(c) {
    const auto& rc = c.render;
    const int waves = std::max(1, std::min(rc.coarse_waves, rc.n_samples));
    if (waves > 1)
      waves_ = std::make_unique<CoarseWaves>(c.rt, c.max_rays, rc.n_samples, waves,
                                             c.encoder_width, rc.stop_transmittance);
  }
  SampleSet sample(const SampleRequest& r) override {
    SampleSet s;
    const cl::Buffer* enc = nullptr;  // the full layout's encodings, when present
    if (I > 0) {
      s = importance_pass(*this, r, waves_.get());
      if (s.encoded) enc = &buf.enc;
    } else {
      // Uniform-only sampling (GeoNLF's, SG-NLF's): the coarse pass found each ray's
      // termination point; the sample set is the same uniform one (drawn again: the same seed
      // and step give the same samples), and its live prefix reuses the pass's encodings
      // (enc_c: the layout of S samples per ray is the merged layout here).
      s.coarse = coarse_pass(*this, r, waves_.get());
      parts.rays.uniform(buf.origins, buf.directions, r.n_rays, r.jitter, r.seed, r.step, buf.t,
                         buf.x);
      field.clamp(buf.x, r.n_rays * S);
      s.n_rays = r.n_rays, s.per_ray = S;
      if (r.reuse_encodings) enc = &buf.enc_c;
    }
    SampleCompaction& live = *parts.live;
    s.rows = live.select(r.n_rays, s.per_ray, buf.t_c, buf.w_c, buf.t, buf.x);
    if (enc)
      live.gather_encodings(r.n_rays, s.per_ray, *enc);
    else
      live.encode(field.encoder, field.params, field.grid_offset);
    s.encoded = true;  // the live rows' encodings
    s.compacted = true;
    return s;
  }

 private:
  std::unique_ptr<CoarseWaves> waves_;  // render.coarse_waves > 1
};

}  // namespace

SamplerKind terminated() {
  SamplerKind k;
  k.name = "terminated";
  k.per_ray = [](const render::RenderConfig& rc) { return rc.n_samples + rc.n_importance; };
  k.check = [](const render::RenderConfig& rc, const std::string& key) {
    require_setting(rc.stop_transmittance > 0.0f, key, "terminated",
                    "early termination (render.stop_transmittance > 0)");
  };
  k.make = [](const SamplerContext& c) -> std::unique_ptr<Sampler> {
    return std::make_unique<TerminatedSampler>(c);
  };
  return k;
}

}  // namespace sgnlf::pipeline::samplers
