// SG-NLF's hybrid spectral-geometric encoding (method.md §4.1) as a field::Encoder:
//   f_hyb(x) = [f_geo(x), λ·Ψ(x)],  f_geo the hash grid, Ψ the spectral-embedding MLP.
// The hash grid lives in the model's flat buffer and trains with the range loss. Ψ owns its
// parameters and trains only on the spectral loss (spectral_gradient; the optimiser that steps
// it is its loss term's, pipeline::SpectralLoss), on its own schedule: the range loss reaches the positions through Ψ (dL/dx, for the pose gradients) but
// never Ψ's weights, so Ψ stays a spectral embedding of the surface (the reading of method.md
// §4.1 this project takes). With λ = 0 Ψ is not evaluated and f_hyb = [f_geo, 0].
// Without the geometric part (`geometric` false: the ablation "spectral only", method.md §5)
// f_hyb = λ·Ψ(x): the encoder has no parameters of its own and the positions' gradient is Ψ's.
#pragma once
#include <memory>

#include "field/encoder.hpp"
#include "field/hash_grid.hpp"
#include "spectral/fusion.hpp"
#include "spectral/psi.hpp"
#include "spectral/spectral_objective.hpp"

namespace sgnlf::spectral {

class HybridEncoder : public field::Encoder {
 public:
  HybridEncoder(cl::Runtime& rt, const field::HashGridConfig& grid, const PsiSpec& psi,
                const SpectralLossConfig& loss, bool geometric = true);

  int width() const override { return geo_width() + psi_spec_.k; }
  // f_geo and λΨ, each normalised on its own where the pose graph matches features; λΨ alone
  // without the grid.
  std::vector<int> parts() const override {
    return geometric_ ? std::vector<int>{geo_width(), psi_spec_.k} : std::vector<int>{psi_spec_.k};
  }
  size_t n_params() const override { return geometric_ ? grid_.n_params() : 0; }
  bool geometric() const { return geometric_; }
  // The grid's slice from `seed`; Ψ from init_psi_params(seed ^ 0x5151).
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) override;
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
               cl::Buffer& enc) override;
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                cl::Buffer* d_x) override;
  int levels() const override { return grid_.config().levels; }
  void set_level_weights(const std::vector<float>& w) override { grid_.set_level_weights(w); }

  // Fusion weight λ(t) of the following forward/backward calls (FusionRamp), in [0, 1].
  void set_lambda(float lambda);
  float lambda() const { return lambda_; }

  // The spectral loss of a batch of surface samples (normalised box, weights summing to 1) and
  // its gradient with respect to Ψ's parameters into psi_grad(). Returns the loss (blocking).
  double spectral_gradient(const std::vector<SurfacePoint>& batch);
  // Ψ's parameters (psi_params() floats) and the gradient of the last spectral_gradient(), for
  // the optimiser that steps them.
  cl::Buffer& psi_param_buffer() { return psi_params_; }
  const cl::Buffer& psi_grad() const { return psi_grad_; }
  // Ψ at points (N × K, normalised box), blocking.
  std::vector<float> psi_at(const std::vector<Eigen::Vector3d>& x);

  int k() const { return psi_spec_.k; }
  size_t psi_params() const { return psi_.n_params(); }
  // Ψ's parameters, host copies (checkpoints) and their restoration (IoError on a size
  // mismatch, naming both counts).
  std::vector<float> read_psi() const;
  void write_psi(const std::vector<float>& params);

 private:
  void ensure(int n);
  int geo_width() const { return geometric_ ? grid_.n_output() : 0; }
  cl::Runtime& rt_;
  bool geometric_;
  field::HashGrid grid_;
  PsiSpec psi_spec_;
  field::Mlp psi_;
  SpectralFusion fusion_;
  std::unique_ptr<SpectralObjective> objective_;
  cl::Buffer psi_params_, psi_grad_, psi_scratch_grad_;
  field::MlpContext ctx_;
  cl::Buffer geo_, psi_out_, d_geo_, d_psi_, d_x_psi_, zeros_;
  cl::Kernel accumulate_;
  size_t capacity_ = 0;
  float lambda_ = 0.0f;
  const cl::Buffer* psi_x_ = nullptr;  // points of Ψ's activations in ctx_ (nullptr: none)
  int psi_n_ = 0;
};

}  // namespace sgnlf::spectral
