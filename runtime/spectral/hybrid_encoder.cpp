// HybridEncoder (hybrid_encoder.hpp).
#include "spectral/hybrid_encoder.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace sgnlf::spectral {
namespace {
cl::Buffer floats(cl::Runtime& rt, size_t n) { return cl::Buffer(rt, std::max<size_t>(n, 1) * 4); }
}  // namespace

HybridEncoder::HybridEncoder(cl::Runtime& rt, const field::HashGridConfig& grid, const PsiSpec& psi,
                             const SpectralLossConfig& loss, bool geometric)
    : rt_(rt),
      geometric_(geometric),
      grid_(rt, grid),
      psi_spec_((psi.validate(), psi)),
      psi_(rt, psi_mlp_spec(psi)),
      fusion_(rt, geometric ? grid_.n_output() : 0, psi.k) {
  objective_ = std::make_unique<SpectralObjective>(rt, psi_, loss);
  psi_params_ = floats(rt, psi_.n_params());
  psi_grad_ = floats(rt, psi_.n_params());
  psi_scratch_grad_ = floats(rt, psi_.n_params());
  psi_grad_.fill_zero();
  accumulate_ = rt.kernel("field/accumulate.cl", "field_accumulate");
}

void HybridEncoder::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) {
  if (geometric_) grid_.init_params(host_params, offset, seed);
  std::vector<float> p(psi_.n_params(), 0.0f);
  init_psi_params(psi_, psi_spec_, p, 0, seed ^ 0x5151);
  psi_params_.write_vec(p);
}

void HybridEncoder::set_lambda(float lambda) {
  require(std::isfinite(lambda) && lambda >= 0.0f && lambda <= 1.0f,
          "HybridEncoder: fusion weight lambda " + std::to_string(lambda) + " not in [0, 1]");
  lambda_ = lambda;
}

void HybridEncoder::ensure(int n) {
  if (size_t(n) <= capacity_) return;
  const size_t N = size_t(n);
  geo_ = floats(rt_, N * size_t(geo_width()));
  d_geo_ = floats(rt_, N * size_t(geo_width()));
  psi_out_ = floats(rt_, N * size_t(psi_spec_.k));
  psi_out_.fill_zero();  // λ = 0 reads it (times 0): keep it finite
  d_psi_ = floats(rt_, N * size_t(psi_spec_.k));
  d_x_psi_ = floats(rt_, N * 3);
  if (!geometric_) {  // λ = 0 without the grid: the positions' gradient is 0
    zeros_ = floats(rt_, N * 3);
    zeros_.fill_zero();
  }
  capacity_ = N;
}

void HybridEncoder::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                            cl::Buffer& enc) {
  ensure(n);
  if (geometric_) grid_.forward(params, offset, x, n, geo_);
  psi_x_ = nullptr;
  if (lambda_ > 0.0f) {
    psi_.forward(psi_params_, 0, x, n, psi_out_, ctx_);
    psi_x_ = &x, psi_n_ = n;
  }
  fusion_.forward(geo_, psi_out_, n, lambda_, enc);
}

void HybridEncoder::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                             const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                             cl::Buffer* d_x) {
  require(size_t(n) <= capacity_, "HybridEncoder::backward: more points than the last forward");
  fusion_.backward(d_enc, n, lambda_, geometric_ ? &d_geo_ : nullptr, d_psi_);
  if (geometric_) {
    grid_.backward(params, offset, x, n, d_geo_, grad, grad_offset, d_x);
  } else if (d_x && lambda_ <= 0.0f) {
    d_x->copy_from(zeros_, size_t(n) * 3 * 4);  // no part depends on x
    return;
  }
  if (!d_x || lambda_ <= 0.0f) return;
  // Ψ's share of dL/dx; its weight gradient goes to a scratch buffer (Ψ trains on L_spe only).
  // The model may encode several point sets before one backward (coarse and importance
  // samples, compacted rows): Ψ's activations are recomputed unless the last forward was on
  // these very points.
  if (psi_x_ != &x || psi_n_ != n) psi_.forward(psi_params_, 0, x, n, psi_out_, ctx_);
  psi_x_ = &x, psi_n_ = n;
  psi_.backward(psi_params_, 0, ctx_, psi_out_, d_psi_, psi_scratch_grad_, 0, &d_x_psi_);
  if (!geometric_) {  // Ψ's share is the whole gradient (the grid's backward wrote none)
    d_x->copy_from(d_x_psi_, size_t(n) * 3 * 4);
    return;
  }
  accumulate_.set_args(n * 3, d_x_psi_, *d_x);
  accumulate_.launch({cl::round_up(size_t(n) * 3, 64)}, {64});
}

double HybridEncoder::spectral_gradient(const std::vector<SurfacePoint>& batch) {
  return objective_->loss_and_grad(psi_params_, 0, batch, psi_grad_, 0).loss;
}

std::vector<float> HybridEncoder::psi_at(const std::vector<Eigen::Vector3d>& x) {
  return objective_->evaluate(psi_params_, 0, x);
}

std::vector<float> HybridEncoder::read_psi() const { return psi_params_.read_vec<float>(psi_.n_params()); }

void HybridEncoder::write_psi(const std::vector<float>& params) {
  if (params.size() != psi_.n_params())
    throw IoError("spectral embedding state has " + std::to_string(params.size()) +
                  " parameters, the model's Psi " + std::to_string(psi_.n_params()));
  psi_params_.write_vec(params);
}

}  // namespace sgnlf::spectral
