// The spectral loss of method.md §4.1 on the outputs of Ψ at the five evaluations of each
// surface sample (x, x + h t1, x − h t1, x + h t2, x − h t2), reduced in double on the host.
//   Ũ = U − Σ w U (centred outputs),  D_a = (Ψ(x + h t_a) − Ψ(x − h t_a)) / 2h,
//   S = Ũᵀ W Ũ,  P = Σ_a D_aᵀ W D_a  (W = diag(w), weights summing to 1 stand for dA / A).
// Forms:
//   ky_fan   (default): L = tr(S⁻¹P) + β‖S − I‖²_F; minimised by an orthonormal basis of the
//            span of the first K non-constant eigenfunctions (Ky Fan).
//   per_mode (paper-literal ablation): L = Σ_k P_kk/S_kk + λ_n Σ_k (S_kk − 1)² + λ_o Σ_{k≠l} S_kl².
// For a loss f(S, P) with G_S = ∂f/∂S, G_P = ∂f/∂P (both symmetric here):
//   dL/dŨ = W Ũ (G_S + G_Sᵀ),  dL/dD_a = W D_a (G_P + G_Pᵀ),
// which for ky_fan is method.md's dL/dU = 2WŨ(−S⁻¹PS⁻¹ + 2β(S − I)), dL/dD_a = 2 W D_a S⁻¹.
#pragma once
#include <Eigen/Core>

#include <string>
#include <vector>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::spectral {

enum class SpectralLossForm { ky_fan, per_mode };
inline constexpr std::pair<SpectralLossForm, const char*> kSpectralLossForms[] = {
    {SpectralLossForm::ky_fan, "ky_fan"}, {SpectralLossForm::per_mode, "per_mode"}};

struct SpectralLossConfig {
  SpectralLossForm form = SpectralLossForm::ky_fan;
  double beta = 1e-2;          // ky_fan normalisation weight
  double lambda_norm = 1.0;    // per_mode normalisation weight
  double lambda_ortho = 1.0;   // per_mode orthogonality weight
  double h = 5e-3;             // tangential central-difference step (unit-box coordinates)
  // The keys and ranges (core/config_fields.hpp).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("form", s.form, config::choices(kSpectralLossForms));
    v("beta", s.beta, 0.0, 1e6);
    v("lambda_norm", s.lambda_norm, 0.0, 1e6);
    v("lambda_ortho", s.lambda_ortho, 0.0, 1e6);
    v("h", s.h, 1e-5, 0.1);
  }
  void validate() const;
  static SpectralLossConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

// The five evaluation blocks, each n rows of the batched Ψ input/output.
constexpr int kEvalsPerSample = 5;

struct SpectralLossResult {
  double loss = 0;
  Eigen::MatrixXd S, P;   // K×K
  Eigen::VectorXd mean;   // Σ w U
};

// Y: 5·n rows × k floats, row-major, block b = rows [b·n, (b+1)·n) in the order above.
// w: n weights summing to 1, or empty for 1/n. dY (optional, 5·n × k) receives dL/dY.
// Throws NumericError when S is not positive definite or the loss is not finite.
SpectralLossResult spectral_loss(const float* Y, size_t n, int k, const std::vector<double>& w,
                                 const SpectralLossConfig& cfg, float* dY);

// Double-precision variant used by the gradient tests (same math).
SpectralLossResult spectral_loss(const double* Y, size_t n, int k, const std::vector<double>& w,
                                 const SpectralLossConfig& cfg, double* dY);

// Accumulates S and P over many batches (the large evaluation sets of the readout).
class SpectralMoments {
 public:
  explicit SpectralMoments(int k);
  // One batch of 5·n rows (layout as above) with its weights (not normalised per batch).
  void add(const float* Y, size_t n, const std::vector<double>& w, double h);
  // Centred S, P normalised by the total weight.
  Eigen::MatrixXd S() const;
  Eigen::MatrixXd P() const;
  Eigen::VectorXd mean() const;

 private:
  int k_;
  double total_ = 0;
  Eigen::VectorXd sum_;
  Eigen::MatrixXd m2_, p_;
};

}  // namespace sgnlf::spectral
