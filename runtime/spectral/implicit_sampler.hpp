// Area-uniform surface samples on an implicit surface {f = 0} (method.md §4.1 "surface
// samples"): uniform box points with |f| < band are projected by a few Newton steps
// x ← x − f ∇f / |∇f|²; the projected density is ∝ 1/|∇f| (the band's thickness along the normal
// is 2·band/|∇f|), so each candidate is kept with probability |∇f| / max|∇f| (rejection
// thinning), which leaves an area-uniform set. Normals are ∇f/|∇f|; tangents from tangent_frame.
// Works for any f (an SDF, an analytic function, or later the neural field's density level set).
#pragma once
#include <functional>

#include "spectral/surface.hpp"

namespace sgnlf::spectral {

struct ImplicitFunction {
  std::function<double(const Eigen::Vector3d&)> value;
  // Optional; central differences with step 1e-6 when empty.
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> gradient;
  Eigen::Vector3d grad(const Eigen::Vector3d& x) const;
};

struct ImplicitSamplerConfig {
  Eigen::Vector3d box_min = Eigen::Vector3d::Constant(-1), box_max = Eigen::Vector3d::Constant(1);
  double band = 0.01;         // candidates need |f| < band
  int newton_steps = 3;       // 1–3 per method.md
  double max_residual = 1e-6; // |f| after projection above this: candidate dropped
  bool thin = true;           // rejection thinning by |∇f| (off only to show its effect)
  size_t batch = 1 << 16;     // box candidates per round
  size_t max_candidates = size_t(1) << 30;
  void validate() const;
};

struct ImplicitSamplerStats {
  size_t candidates = 0, in_band = 0, projected = 0, accepted = 0;
  double grad_max = 0;  // max |∇f| used for thinning
};

std::vector<SurfacePoint> sample_implicit(const ImplicitFunction& f, const ImplicitSamplerConfig& cfg,
                                          size_t n, Rng& rng, ImplicitSamplerStats* stats = nullptr);

}  // namespace sgnlf::spectral
