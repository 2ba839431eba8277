// Spectral loss, its exact output gradients and the moment accumulator (spectral_loss.hpp).
#include "core/config_fields.hpp"
#include "spectral/spectral_loss.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::spectral {

void SpectralLossConfig::validate() const { config::check_fields(*this, "spectral loss"); }

SpectralLossConfig SpectralLossConfig::from_json(const Json& j, const std::string& where) {
  SpectralLossConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);  // form: ky_fan or per_mode
  r.finish();
  c.validate();
  return c;
}

namespace {

using Mat = Eigen::MatrixXd;
using RowMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

template <typename T>
SpectralLossResult loss_impl(const T* Y, size_t n, int k, const std::vector<double>& w_in,
                             const SpectralLossConfig& cfg, T* dY) {
  require(n >= 2 && k >= 1, "spectral_loss: need n >= 2 samples and k >= 1 outputs");
  require(w_in.empty() || w_in.size() == n, "spectral_loss: weights size != n");
  Eigen::VectorXd w = Eigen::VectorXd::Constant(n, 1.0 / double(n));
  if (!w_in.empty()) w = Eigen::Map<const Eigen::VectorXd>(w_in.data(), n);
  auto block = [&](int b) {
    return Eigen::Map<const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
               Y + size_t(b) * n * k, n, k).template cast<double>();
  };
  SpectralLossResult res;
  const RowMat U = block(0);
  res.mean = U.transpose() * w;
  const RowMat Ut = U.rowwise() - res.mean.transpose();
  const double inv2h = 1.0 / (2 * cfg.h);
  RowMat D[2] = {(block(1) - block(2)) * inv2h, (block(3) - block(4)) * inv2h};
  res.S = Ut.transpose() * w.asDiagonal() * Ut;
  res.P = D[0].transpose() * w.asDiagonal() * D[0] + D[1].transpose() * w.asDiagonal() * D[1];
  const Mat I = Mat::Identity(k, k);
  Mat GS, GP;
  if (cfg.form == SpectralLossForm::ky_fan) {
    Eigen::LLT<Mat> llt(res.S);
    if (llt.info() != Eigen::Success || !(llt.rcond() > 1e-13))
      throw NumericError("spectral_loss: S is not positive definite (collapsed outputs)");
    const Mat Sinv = llt.solve(I);
    res.loss = (Sinv * res.P).trace() + cfg.beta * (res.S - I).squaredNorm();
    GS = -Sinv * res.P * Sinv + 2 * cfg.beta * (res.S - I);
    GP = Sinv;
  } else {
    GS = 2 * cfg.lambda_ortho * res.S;
    GP = Mat::Zero(k, k);
    res.loss = 0;
    for (int i = 0; i < k; ++i) {
      const double s = res.S(i, i), p = res.P(i, i);
      if (!(s > 0)) throw NumericError("spectral_loss: zero-norm output " + std::to_string(i));
      res.loss += p / s + cfg.lambda_norm * (s - 1) * (s - 1);
      GS(i, i) = -p / (s * s) + 2 * cfg.lambda_norm * (s - 1);
      GP(i, i) = 1 / s;
      for (int j = 0; j < k; ++j)
        if (j != i) res.loss += cfg.lambda_ortho * res.S(i, j) * res.S(i, j);
    }
  }
  if (!std::isfinite(res.loss)) throw NumericError("spectral_loss: loss is not finite");
  if (!dY) return res;
  const Mat GS2 = GS + GS.transpose(), GP2 = GP + GP.transpose();
  RowMat dUt = w.asDiagonal() * Ut * GS2;
  // Centring backward: Ũ_j = U_j − Σ_i w_i U_i  =>  dU_i = dŨ_i − w_i Σ_j dŨ_j.
  const Eigen::RowVectorXd colsum = dUt.colwise().sum();
  dUt -= w * colsum;
  auto out = [&](int b) {
    return Eigen::Map<Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        dY + size_t(b) * n * k, n, k);
  };
  out(0) = dUt.cast<T>();
  for (int a = 0; a < 2; ++a) {
    const RowMat dD = (w.asDiagonal() * D[a] * GP2) * inv2h;
    out(1 + 2 * a) = dD.cast<T>();
    out(2 + 2 * a) = (-dD).cast<T>();
  }
  return res;
}

}  // namespace

SpectralLossResult spectral_loss(const float* Y, size_t n, int k, const std::vector<double>& w,
                                 const SpectralLossConfig& cfg, float* dY) {
  return loss_impl(Y, n, k, w, cfg, dY);
}
SpectralLossResult spectral_loss(const double* Y, size_t n, int k, const std::vector<double>& w,
                                 const SpectralLossConfig& cfg, double* dY) {
  return loss_impl(Y, n, k, w, cfg, dY);
}

SpectralMoments::SpectralMoments(int k)
    : k_(k), sum_(Eigen::VectorXd::Zero(k)), m2_(Mat::Zero(k, k)), p_(Mat::Zero(k, k)) {}

void SpectralMoments::add(const float* Y, size_t n, const std::vector<double>& w, double h) {
  require(w.size() == n, "SpectralMoments::add: weights size != n");
  const double inv2h = 1.0 / (2 * h);
  Eigen::VectorXd u(k_), d(k_);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < k_; ++c) u[c] = Y[i * k_ + c];
    sum_ += w[i] * u;
    m2_.noalias() += w[i] * u * u.transpose();
    for (int a = 0; a < 2; ++a) {
      for (int c = 0; c < k_; ++c)
        d[c] = (double(Y[((1 + 2 * a) * n + i) * k_ + c]) - Y[((2 + 2 * a) * n + i) * k_ + c]) * inv2h;
      p_.noalias() += w[i] * d * d.transpose();
    }
    total_ += w[i];
  }
}

Eigen::VectorXd SpectralMoments::mean() const { return sum_ / total_; }
Eigen::MatrixXd SpectralMoments::S() const {
  const Eigen::VectorXd mu = mean();
  return m2_ / total_ - mu * mu.transpose();
}
Eigen::MatrixXd SpectralMoments::P() const { return p_ / total_; }

Json SpectralLossConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::spectral
