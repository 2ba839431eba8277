// "importance": a density-only coarse pass over the uniform samples, n_importance samples
// drawn from its weights and merged (S + I per ray); the coarse encodings reused when allowed
// (EncodingReuse).
#include "pipeline/model/samplers/sampler_base.hpp"

namespace sgnlf::pipeline::samplers {
namespace {

class ImportanceSampler final : public SamplerBase {
 public:
  using SamplerBase::SamplerBase;
  SampleSet sample(const SampleRequest& r) override { return importance_pass(*this, r, nullptr); }
};

}  // namespace

SamplerKind importance() {
  SamplerKind k;
  k.name = "importance";
  k.per_ray = [](const render::RenderConfig& rc) { return rc.n_samples + rc.n_importance; };
  k.check = [](const render::RenderConfig& rc, const std::string& key) {
    require_setting(rc.n_importance > 0, key, "importance", "render.n_importance > 0");
  };
  k.make = [](const SamplerContext& c) -> std::unique_ptr<Sampler> {
    return std::make_unique<ImportanceSampler>(c);
  };
  return k;
}

}  // namespace sgnlf::pipeline::samplers
