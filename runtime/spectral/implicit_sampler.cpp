// Band sampling, Newton projection and |∇f| rejection thinning (implicit_sampler.hpp).
#include "spectral/implicit_sampler.hpp"

#include <cmath>

#include "core/error.hpp"

namespace sgnlf::spectral {

Eigen::Vector3d ImplicitFunction::grad(const Eigen::Vector3d& x) const {
  if (gradient) return gradient(x);
  constexpr double e = 1e-6;
  Eigen::Vector3d g;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d a = x, b = x;
    a[i] += e;
    b[i] -= e;
    g[i] = (value(a) - value(b)) / (2 * e);
  }
  return g;
}

void ImplicitSamplerConfig::validate() const {
  const std::string w = "implicit sampler";
  check_range(w, "band", band, 1e-9, 1.0);
  check_range(w, "newton_steps", newton_steps, 1, 20);
  check_range(w, "max_residual", max_residual, 0.0, 1.0);
  check_range<size_t>(w, "batch", batch, 1, size_t(1) << 30);
  if (!((box_max - box_min).minCoeff() > 0)) throw ConfigError(w + ": empty box");
}

std::vector<SurfacePoint> sample_implicit(const ImplicitFunction& f, const ImplicitSamplerConfig& cfg,
                                          size_t n, Rng& rng, ImplicitSamplerStats* stats) {
  cfg.validate();
  require(bool(f.value), "sample_implicit: ImplicitFunction has no value function");
  struct Candidate {
    SurfacePoint p;
    double g, u;
  };
  std::vector<Candidate> pool;
  ImplicitSamplerStats st;
  const Eigen::Vector3d ext = cfg.box_max - cfg.box_min;
  for (;;) {
    for (size_t c = 0; c < cfg.batch; ++c) {
      Eigen::Vector3d x;
      for (int i = 0; i < 3; ++i) x[i] = cfg.box_min[i] + ext[i] * rng.uniform_double();
      const double u = rng.uniform_double();  // drawn for every candidate: fixed stream layout
      ++st.candidates;
      double v = f.value(x);
      if (!(std::fabs(v) < cfg.band)) continue;
      ++st.in_band;
      // The thinning density is that of the band point, before projection.
      Eigen::Vector3d g = f.grad(x);
      const double g0 = g.norm();
      for (int s = 0; s < cfg.newton_steps && g.squaredNorm() > 0; ++s) {
        x -= v * g / g.squaredNorm();
        v = f.value(x);
        g = f.grad(x);
      }
      if (!(std::fabs(v) <= cfg.max_residual) || !(g.norm() > 0)) continue;
      ++st.projected;
      Candidate cand{{}, g0, u};
      cand.p.x = x;
      cand.p.n = g.normalized();
      tangent_frame(cand.p.n, cand.p.t1, cand.p.t2);
      pool.push_back(cand);
      st.grad_max = std::max(st.grad_max, g0);
    }
    size_t accepted = 0;
    for (const auto& c : pool)
      if (!cfg.thin || c.u * st.grad_max < c.g) ++accepted;
    if (accepted >= n) break;
    if (st.candidates >= cfg.max_candidates)
      throw NumericError("sample_implicit: only " + std::to_string(accepted) + " of " +
                         std::to_string(n) + " surface points after " +
                         std::to_string(st.candidates) + " box candidates (band " +
                         std::to_string(cfg.band) + ")");
  }
  std::vector<SurfacePoint> out;
  out.reserve(n);
  for (const auto& c : pool) {
    if (out.size() == n) break;
    if (!cfg.thin || c.u * st.grad_max < c.g) {
      out.push_back(c.p);
      out.back().w = 1.0 / double(n);
    }
  }
  st.accepted = out.size();
  if (stats) *stats = st;
  return out;
}

}  // namespace sgnlf::spectral
