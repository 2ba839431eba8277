// One evaluation of the spectral loss on Ψ (method.md §4.1): the 5 evaluations per surface sample
// (x, x ± h t1, x ± h t2) in one batched forward, outputs read back (K floats each), loss and
// output gradients in double on the host, then the Mlp backward on the device, which overwrites
// Ψ's slice of the gradient buffer (scaled by `weight`, e.g. λ_spe inside the full model).
// Also batched forward-only evaluation for readouts and pictures.
#pragma once
#include "field/mlp.hpp"
#include "spectral/spectral_loss.hpp"
#include "spectral/surface.hpp"

namespace sgnlf::spectral {

// Row-major 5·n × 3 inputs in the block order of spectral_loss.hpp.
std::vector<float> five_point_inputs(const std::vector<SurfacePoint>& pts, size_t begin, size_t n, double h);

class SpectralObjective {
 public:
  SpectralObjective(cl::Runtime& rt, field::Mlp& psi, const SpectralLossConfig& cfg);

  // Loss on `pts` (weights from pts[i].w, renormalised) and dL/dparams·weight into
  // grad[grad_offset, + n_params). Blocks until the outputs are read; backward is enqueued.
  SpectralLossResult loss_and_grad(const cl::Buffer& params, size_t offset, const std::vector<SurfacePoint>& pts,
                                   cl::Buffer& grad, size_t grad_offset, double weight = 1.0);

  // S, P and the mean over a large point set, in chunks (weights pts[i].w).
  SpectralMoments moments(const cl::Buffer& params, size_t offset, const std::vector<SurfacePoint>& pts,
                          size_t chunk = 32768);

  // Ψ at points (N × K floats), in chunks.
  std::vector<float> evaluate(const cl::Buffer& params, size_t offset, const std::vector<Eigen::Vector3d>& x,
                              size_t chunk = 65536);

  const SpectralLossConfig& config() const { return cfg_; }

 private:
  cl::Runtime& rt_;
  field::Mlp& psi_;
  SpectralLossConfig cfg_;
  field::MlpContext ctx_, eval_ctx_;
  cl::Buffer in_, out_, d_out_, eval_in_, eval_out_;
  size_t cap_ = 0, eval_cap_ = 0;
};

}  // namespace sgnlf::spectral
