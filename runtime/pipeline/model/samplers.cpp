// The sampling strategies of sampler.hpp: Uniform, Importance (with encoding reuse), Terminated
// (compaction after early termination, its coarse pass in waves) and Surface, and the coarse
// pass Importance and Terminated share.
#include <string>

#include "core/error.hpp"
#include "pipeline/model/model_detail.hpp"
#include "pipeline/model/sampler.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

const char* strategy_name(SampleStrategy s) {
  switch (s) {
    case SampleStrategy::Uniform: return "uniform";
    case SampleStrategy::Importance: return "importance";
    case SampleStrategy::Terminated: return "terminated";
    case SampleStrategy::Surface: return "surface";
  }
  return "?";
}

SampleStrategy protocol_strategy(const render::RenderConfig& rc) {
  if (rc.stop_transmittance > 0.0f) return SampleStrategy::Terminated;
  return rc.n_importance > 0 ? SampleStrategy::Importance : SampleStrategy::Uniform;
}

namespace {

// Every strategy's shared parts.
struct Base : Sampler {
  Base(const render::RenderConfig& rc, const SamplerParts& p, const SampleBuffers& b,
       const SamplerField& f)
      : S(rc.n_samples), I(rc.n_importance), parts(p), buf(b), field(f) {}
  int S, I;
  SamplerParts parts;
  SampleBuffers buf;
  SamplerField field;
};

class UniformSampler final : public Base {
 public:
  using Base::Base;
  SampleStrategy strategy() const override { return SampleStrategy::Uniform; }
  SampleSet sample(const SampleRequest& r) override {
    parts.rays.uniform(buf.origins, buf.directions, r.n_rays, r.jitter, r.seed, r.step, buf.t,
                       buf.x);
    field.clamp(buf.x, r.n_rays * S);
    SampleSet s;
    s.strategy = strategy();
    s.n_rays = r.n_rays, s.per_ray = S, s.rows = s.samples();
    return s;
  }
};

// The density-only pass over the uniform samples (t_c, x_c): encodings into enc_c, σ logits into
// h0, weights into w_c; in render.coarse_waves waves with CoarseWaves. Returns the samples
// evaluated.
long coarse_pass(Base& b, const SampleRequest& r) {
  const int n_c = r.n_rays * b.S;
  b.parts.rays.uniform(b.buf.origins, b.buf.directions, r.n_rays, r.jitter, r.seed, r.step,
                       b.buf.t_c, b.buf.x_c);
  b.field.clamp(b.buf.x_c, n_c);
  const auto weights = [&] { b.field.weights(b.buf.t_c, b.buf.h0, r.n_rays, b.S, b.buf.w_c); };
  if (b.parts.waves)
    return b.parts.waves->run(r.n_rays, b.buf.x_c, b.buf.w_c, b.buf.enc_c, b.buf.h0,
                              b.field.density, weights);
  const cl::Buffer& dens = b.field.density(b.buf.x_c, n_c, b.buf.enc_c);
  b.field.sigma(dens, n_c, b.buf.h0);
  weights();
  return n_c;
}

class ImportanceSampler final : public Base {
 public:
  using Base::Base;
  SampleStrategy strategy() const override { return SampleStrategy::Importance; }
  SampleSet sample(const SampleRequest& r) override {
    SampleSet s;
    s.coarse = coarse_pass(*this, r);
    EncodingReuse& reuse = *parts.reuse;
    parts.rays.importance(buf.origins, buf.directions, r.n_rays, S, buf.t_c, buf.w_c, r.jitter,
                          r.seed, r.step, buf.t, buf.x, reuse.sources());
    const int M = S + I;
    field.clamp(buf.x, r.n_rays * M);
    // The merged set's coarse samples were encoded by the coarse pass with the same parameters:
    // only the importance samples need the hash grid (exact; the coarse positions are copied
    // over so that the backward scatters where the forward read).
    if (r.reuse_encodings)
      reuse.encode_importance(r.n_rays, buf.x, field.encoder, field.params, field.grid_offset);
    reuse.merge(r.n_rays, buf.x_c, buf.enc_c, buf.x, buf.enc);
    s.strategy = strategy();
    s.n_rays = r.n_rays, s.per_ray = M, s.rows = s.samples();
    s.encoded = r.reuse_encodings;
    return s;
  }
};

class TerminatedSampler final : public Base {
 public:
  TerminatedSampler(const render::RenderConfig& rc, const SamplerParts& p, const SampleBuffers& b,
                    const SamplerField& f)
      : Base(rc, p, b, f) {
    if (I > 0) importance_ = std::make_unique<ImportanceSampler>(rc, p, b, f);
  }
  SampleStrategy strategy() const override { return SampleStrategy::Terminated; }
  SampleSet sample(const SampleRequest& r) override {
    SampleSet s;
    const cl::Buffer* enc = nullptr;  // the full layout's encodings, when present
    if (importance_) {
      s = importance_->sample(r);
      if (s.encoded) enc = &buf.enc;
    } else {
      // Uniform-only sampling (GeoNLF's, SG-NLF's): the coarse pass found each ray's
      // termination point; the sample set is the same uniform one (drawn again: the same seed
      // and step give the same samples), and its live prefix reuses the pass's encodings
      // (enc_c: the layout of S samples per ray is the merged layout here).
      s.coarse = coarse_pass(*this, r);
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
    s.strategy = strategy();
    s.encoded = true;  // the live rows' encodings
    s.compacted = true;
    return s;
  }

 private:
  std::unique_ptr<ImportanceSampler> importance_;
};

class SurfaceTrainingSampler final : public Base {
 public:
  using Base::Base;
  SampleStrategy strategy() const override { return SampleStrategy::Surface; }
  SampleSet sample(const SampleRequest& r) override {
    render::SurfaceSampler& surface = *parts.surface;
    const int M = surface.samples();
    surface.sample(buf.origins, buf.directions, buf.targets, r.n_rays, r.jitter, r.seed, r.step,
                   buf.t, buf.x);
    field.clamp(buf.x, r.n_rays * M);
    SampleSet s;
    s.strategy = strategy();
    s.n_rays = r.n_rays, s.per_ray = M, s.rows = s.samples();
    return s;
  }
};

void need(const void* part, const char* what, SampleStrategy s) {
  if (!part)
    throw Error(std::string("make_sampler: the ") + strategy_name(s) + " strategy needs " + what);
}

}  // namespace

std::unique_ptr<Sampler> make_sampler(SampleStrategy s, const render::RenderConfig& rc,
                                      const SamplerParts& parts, const SampleBuffers& buffers,
                                      const SamplerField& field) {
  switch (s) {
    case SampleStrategy::Uniform:
      return std::make_unique<UniformSampler>(rc, parts, buffers, field);
    case SampleStrategy::Importance:
      need(parts.reuse, "the encoding reuse (render.n_importance > 0)", s);
      return std::make_unique<ImportanceSampler>(rc, parts, buffers, field);
    case SampleStrategy::Terminated:
      need(parts.live, "the sample compaction (render.stop_transmittance > 0)", s);
      if (rc.n_importance > 0) need(parts.reuse, "the encoding reuse (render.n_importance > 0)", s);
      return std::make_unique<TerminatedSampler>(rc, parts, buffers, field);
    case SampleStrategy::Surface:
      need(parts.surface, "the surface sampler (render.surface_band_samples > 0)", s);
      return std::make_unique<SurfaceTrainingSampler>(rc, parts, buffers, field);
  }
  throw Error("make_sampler: unknown strategy");
}

}  // namespace sgnlf::pipeline
