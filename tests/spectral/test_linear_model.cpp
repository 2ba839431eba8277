// The loss + readout pipeline without an MLP: Ψ = Aᵀφ(x) with φ the 19 monomials of degree 1–3,
// whose restrictions to the sphere span exactly the harmonics l ≤ 3. Training A with the loss's
// output gradients (host Adam, test only) must select the first K = 8 modes (l = 1, 2); the
// Rayleigh–Ritz readout must then give l(l+1)/r².
#include <catch2/catch.hpp>

#include <cmath>

#include "spectral/rayleigh_ritz.hpp"
#include "spectral/spectral_loss.hpp"
#include "spectral/surface.hpp"

using namespace sgnlf;
using namespace sgnlf::spectral;

namespace {

constexpr int kF = 19;

void features(const Eigen::Vector3d& x, double* f) {
  int i = 0;
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; a + b <= 3; ++b)
      for (int c = 0; a + b + c <= 3; ++c)
        if (a + b + c > 0) f[i++] = std::pow(x.x(), a) * std::pow(x.y(), b) * std::pow(x.z(), c);
}

// 5·n × k outputs of the linear model, and the 5·n × kF features.
void evaluate(const Eigen::MatrixXd& A, const std::vector<SurfacePoint>& pts, double h, std::vector<double>& Y,
              Eigen::MatrixXd& Phi) {
  const size_t n = pts.size();
  const int k = int(A.cols());
  Phi.resize(kEvalsPerSample * n, kF);
  for (size_t i = 0; i < n; ++i) {
    const auto& p = pts[i];
    const Eigen::Vector3d xs[5] = {p.x, p.x + h * p.t1, p.x - h * p.t1, p.x + h * p.t2, p.x - h * p.t2};
    for (int b = 0; b < 5; ++b) {
      double f[kF];
      features(xs[b], f);
      for (int j = 0; j < kF; ++j) Phi(b * n + i, j) = f[j];
    }
  }
  const Eigen::MatrixXd out = Phi * A;
  Y.resize(out.size());
  for (Eigen::Index r = 0; r < out.rows(); ++r)
    for (int c = 0; c < k; ++c) Y[r * k + c] = out(r, c);
}

Eigen::VectorXd readout(const Eigen::MatrixXd& A, const Shape& sphere, const SpectralLossConfig& cfg) {
  const auto lat = sphere.lattice(100000);
  std::vector<double> Y, w(lat.size());
  Eigen::MatrixXd Phi;
  evaluate(A, lat, cfg.h, Y, Phi);
  for (size_t i = 0; i < lat.size(); ++i) w[i] = lat[i].w;
  const auto r = spectral_loss(Y.data(), lat.size(), int(A.cols()), w, cfg, nullptr);
  return rayleigh_ritz(r.S, r.P, r.mean).eigenvalues;
}

}  // namespace

TEST_CASE("linear model: the readout of the full degree-3 span gives l(l+1)/r^2", "[readout]") {
  const auto sphere = make_shape(ShapeSpec::preset(ShapeKind::sphere));
  Rng rng(31);
  Eigen::MatrixXd A(kF, 15);
  for (int i = 0; i < A.size(); ++i) A.data()[i] = rng.normal();
  const auto lam = readout(A, *sphere, SpectralLossConfig{});
  const double r2 = 0.64;
  for (int i = 0; i < 15; ++i) {
    const int l = i < 3 ? 1 : i < 8 ? 2 : 3;
    CHECK(lam[i] == Approx(l * (l + 1) / r2).epsilon(1e-4));
  }
}

TEST_CASE("linear model: training with the ky_fan loss selects the first 8 modes", "[readout]") {
  const auto sphere = make_shape(ShapeSpec::preset(ShapeKind::sphere));
  Rng rng(32);
  const int k = 8;
  Eigen::MatrixXd A(kF, k), m = Eigen::MatrixXd::Zero(kF, k), v = Eigen::MatrixXd::Zero(kF, k);
  for (int i = 0; i < A.size(); ++i) A.data()[i] = rng.normal();
  SpectralLossConfig cfg;
  const auto before = readout(A, *sphere, cfg);
  CHECK(before[k - 1] > 1.2 * 6 / 0.64);  // random span: not yet the l ≤ 2 space
  double first = 0, last = 0;
  const int steps = 600;
  for (int t = 1; t <= steps; ++t) {
    const auto pts = sphere->sample(rng, 512);
    std::vector<double> Y;
    Eigen::MatrixXd Phi;
    evaluate(A, pts, cfg.h, Y, Phi);
    std::vector<double> dY(Y.size());
    const double loss = spectral_loss(Y.data(), pts.size(), k, {}, cfg, dY.data()).loss;
    if (t == 1) first = loss;
    last = loss;
    const Eigen::MatrixXd G = Phi.transpose() *
        Eigen::Map<Eigen::Matrix<double, -1, -1, Eigen::RowMajor>>(dY.data(), Phi.rows(), k);
    // Adam (test-only host reference of the update rule), lr 2e-2 cosine-decayed.
    const double lr = 2e-2 * 0.5 * (1 + std::cos(M_PI * t / steps)) + 1e-4;
    m = 0.9 * m + 0.1 * G;
    v = 0.99 * v + 0.01 * G.cwiseProduct(G);
    const double c1 = 1 / (1 - std::pow(0.9, t)), c2 = 1 / (1 - std::pow(0.99, t));
    A.array() -= lr * (m.array() * c1) / ((v.array() * c2).sqrt() + 1e-12);
  }
  INFO("loss " << first << " -> " << last);
  CHECK(last < first);
  const auto lam = readout(A, *sphere, cfg);
  for (int i = 0; i < k; ++i) {
    const int l = i < 3 ? 1 : 2;
    INFO("mode " << i << " learned " << lam[i]);
    CHECK(lam[i] == Approx(l * (l + 1) / 0.64).epsilon(1e-2));
  }
}
