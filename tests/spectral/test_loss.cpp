// Spectral loss: finite-difference check of the output gradients (both forms), moments vs loss,
// and the Rayleigh–Ritz readout's orthonormality after folding.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>

#include "core/rng.hpp"
#include "spectral/rayleigh_ritz.hpp"
#include "spectral/spectral_loss.hpp"

using namespace sgnlf;
using namespace sgnlf::spectral;

namespace {

std::vector<double> random_outputs(Rng& rng, size_t n, int k) {
  std::vector<double> Y(kEvalsPerSample * n * k);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < k; ++c) {
      const double base = rng.normal() + 0.3 * c;
      Y[i * k + c] = base;
      for (int b = 1; b < kEvalsPerSample; ++b) Y[(b * n + i) * k + c] = base + 0.01 * rng.normal();
    }
  return Y;
}

void check_fd(const SpectralLossConfig& cfg, uint64_t seed) {
  Rng rng(seed);
  const size_t n = 48;
  const int k = 5;
  auto Y = random_outputs(rng, n, k);
  std::vector<double> w(n);
  double ws = 0;
  for (auto& x : w) ws += (x = 0.5 + rng.uniform_double());
  for (auto& x : w) x /= ws;
  std::vector<double> dY(Y.size());
  spectral_loss(Y.data(), n, k, w, cfg, dY.data());
  double worst = 0;
  for (int t = 0; t < 200; ++t) {
    const size_t idx = rng.below(uint32_t(Y.size()));
    const double e = 1e-6, y0 = Y[idx];
    Y[idx] = y0 + e;
    const double lp = spectral_loss(Y.data(), n, k, w, cfg, nullptr).loss;
    Y[idx] = y0 - e;
    const double lm = spectral_loss(Y.data(), n, k, w, cfg, nullptr).loss;
    Y[idx] = y0;
    const double fd = (lp - lm) / (2 * e);
    worst = std::max(worst, std::fabs(fd - dY[idx]) / std::max(std::fabs(fd) + std::fabs(dY[idx]), 1e-3));
  }
  INFO("worst symmetric relative error " << worst);
  CHECK(worst < 1e-5);
}

}  // namespace

TEST_CASE("ky_fan loss output gradients match finite differences", "[loss]") {
  SpectralLossConfig cfg;
  check_fd(cfg, 1);
  cfg.beta = 0.3;
  cfg.h = 0.02;
  check_fd(cfg, 2);
}

TEST_CASE("per_mode loss output gradients match finite differences", "[loss]") {
  SpectralLossConfig cfg;
  cfg.form = SpectralLossForm::per_mode;
  check_fd(cfg, 3);
  cfg.lambda_norm = 0.2;
  cfg.lambda_ortho = 3.0;
  check_fd(cfg, 4);
}

TEST_CASE("ky_fan loss value is tr(S^-1 P) + beta |S - I|^2 of the centred outputs", "[loss]") {
  Rng rng(5);
  const size_t n = 100;
  const int k = 3;
  const auto Y = random_outputs(rng, n, k);
  SpectralLossConfig cfg;
  const auto r = spectral_loss(Y.data(), n, k, {}, cfg, nullptr);
  // Direct recomputation, loops only.
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(k, k), P = Eigen::MatrixXd::Zero(k, k);
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(k);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < k; ++c) mu[c] += Y[i * k + c] / n;
  for (size_t i = 0; i < n; ++i)
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b) {
        S(a, b) += (Y[i * k + a] - mu[a]) * (Y[i * k + b] - mu[b]) / n;
        for (int t = 0; t < 2; ++t) {
          const double da = (Y[((1 + 2 * t) * n + i) * k + a] - Y[((2 + 2 * t) * n + i) * k + a]) / (2 * cfg.h);
          const double db = (Y[((1 + 2 * t) * n + i) * k + b] - Y[((2 + 2 * t) * n + i) * k + b]) / (2 * cfg.h);
          P(a, b) += da * db / n;
        }
      }
  const double expect = (S.inverse() * P).trace() + cfg.beta * (S - Eigen::MatrixXd::Identity(k, k)).squaredNorm();
  CHECK(r.loss == Approx(expect).epsilon(1e-12));
  CHECK((r.S - S).norm() < 1e-12);
  CHECK((r.P - P).norm() < 1e-9);
  // A collapsed output is an error, not a NaN.
  auto Yc = Y;
  for (size_t i = 0; i < n; ++i) Yc[i * k + 1] = 2.0;
  CHECK_THROWS_AS(spectral_loss(Yc.data(), n, k, {}, cfg, nullptr), NumericError);
}

TEST_CASE("moments accumulated in batches equal the loss's S and P; readout is orthonormal", "[readout]") {
  Rng rng(6);
  const size_t n = 400;
  const int k = 4, hidden = 6;
  // Outputs of a linear last layer y = W h + b on random hidden features h (5 evaluations).
  std::vector<float> W(k * hidden), b(k);
  for (auto& x : W) x = float(rng.normal());
  for (auto& x : b) x = float(rng.normal());
  std::vector<float> H(kEvalsPerSample * n * hidden), Y(kEvalsPerSample * n * k);
  for (size_t i = 0; i < n; ++i)
    for (int j = 0; j < hidden; ++j) {
      const double base = rng.normal();
      for (int e = 0; e < kEvalsPerSample; ++e) H[(e * n + i) * hidden + j] = float(base + (e ? 0.01 * rng.normal() : 0));
    }
  auto apply = [&](const std::vector<float>& Wl, const std::vector<float>& bl, std::vector<float>& out) {
    for (size_t r = 0; r < kEvalsPerSample * n; ++r)
      for (int c = 0; c < k; ++c) {
        double s = bl[c];
        for (int j = 0; j < hidden; ++j) s += double(Wl[c * hidden + j]) * H[r * hidden + j];
        out[r * k + c] = float(s);
      }
  };
  apply(W, b, Y);
  SpectralLossConfig cfg;
  const auto full = spectral_loss(Y.data(), n, k, {}, cfg, nullptr);
  // Two batches in the moment accumulator (rows split by sample, five blocks each).
  SpectralMoments mom(k);
  for (size_t half = 0; half < 2; ++half) {
    const size_t m = n / 2;
    std::vector<float> Yb(kEvalsPerSample * m * k);
    for (int e = 0; e < kEvalsPerSample; ++e)
      std::copy_n(Y.begin() + (e * n + half * m) * k, m * k, Yb.begin() + e * m * k);
    mom.add(Yb.data(), m, std::vector<double>(m, 1.0), cfg.h);
  }
  CHECK((mom.S() - full.S).norm() < 1e-9 * full.S.norm());
  CHECK((mom.P() - full.P).norm() < 1e-9 * full.P.norm());
  const auto ritz = rayleigh_ritz(mom.S(), mom.P(), mom.mean());
  for (int i = 1; i < k; ++i) CHECK(ritz.eigenvalues[i] >= ritz.eigenvalues[i - 1]);
  fold_readout(ritz, W, b, hidden);
  apply(W, b, Y);
  const auto after = spectral_loss(Y.data(), n, k, {}, cfg, nullptr);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(k, k);
  CHECK((after.S - I).cwiseAbs().maxCoeff() < 1e-4);
  CHECK(after.mean.cwiseAbs().maxCoeff() < 1e-4);
  Eigen::MatrixXd Pd = after.P;
  for (int i = 0; i < k; ++i) {
    CHECK(Pd(i, i) == Approx(ritz.eigenvalues[i]).epsilon(1e-4));
    Pd(i, i) = 0;
  }
  CHECK(Pd.cwiseAbs().maxCoeff() < 1e-4 * ritz.eigenvalues[k - 1]);
}
