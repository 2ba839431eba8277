// "surface": training samples placed by the measured return (render.surface_*,
// render::SurfaceSampler): free samples before the band, the band around the return, samples
// behind it; no coarse pass. Training rays only (test rays have no return).
#include "pipeline/model/samplers/sampler_base.hpp"
#include "render/surface_sampler.hpp"

namespace sgnlf::pipeline::samplers {
namespace {

class SurfaceTrainingSampler final : public SamplerBase {
 public:
  explicit SurfaceTrainingSampler(const SamplerContext& c)
      : SamplerBase(c), surface_(c.rt, c.render, c.scene_scale) {}
  SampleSet sample(const SampleRequest& r) override {
    const int M = surface_.samples();
    surface_.sample(buf.origins, buf.directions, buf.targets, r.n_rays, r.jitter, r.seed, r.step,
                    buf.t, buf.x);
    field.clamp(buf.x, r.n_rays * M);
    SampleSet s;
    s.n_rays = r.n_rays, s.per_ray = M, s.rows = s.samples();
    return s;
  }

 private:
  render::SurfaceSampler surface_;
};

}  // namespace

SamplerKind surface() {
  SamplerKind k;
  k.name = "surface";
  k.per_ray = [](const render::RenderConfig& rc) { return rc.surface_samples(); };
  k.check = [](const render::RenderConfig& rc, const std::string& key) {
    require_setting(rc.surface_sampling(), key, "surface", "render.surface_band_samples > 0");
  };
  k.make = [](const SamplerContext& c) -> std::unique_ptr<Sampler> {
    return std::make_unique<SurfaceTrainingSampler>(c);
  };
  return k;
}

}  // namespace sgnlf::pipeline::samplers
