// "uniform": n_samples stratified samples per ray, every one evaluated (no coarse pass).
#include "pipeline/model/samplers/sampler_base.hpp"

namespace sgnlf::pipeline::samplers {
namespace {

class UniformSampler final : public SamplerBase {
 public:
  using SamplerBase::SamplerBase;
  SampleSet sample(const SampleRequest& r) override {
    parts.rays.uniform(buf.origins, buf.directions, r.n_rays, r.jitter, r.seed, r.step, buf.t,
                       buf.x);
    field.clamp(buf.x, r.n_rays * S);
    SampleSet s;
    s.n_rays = r.n_rays, s.per_ray = S, s.rows = s.samples();
    return s;
  }
};

}  // namespace

SamplerKind uniform() {
  SamplerKind k;
  k.name = "uniform";
  k.per_ray = [](const render::RenderConfig& rc) { return rc.n_samples; };
  k.make = [](const SamplerContext& c) -> std::unique_ptr<Sampler> {
    return std::make_unique<UniformSampler>(c);
  };
  return k;
}

}  // namespace sgnlf::pipeline::samplers
