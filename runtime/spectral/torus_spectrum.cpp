// Fourier–Galerkin solve of the torus's per-order Sturm–Liouville problems (torus_spectrum.hpp).
#include "spectral/torus_spectrum.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace sgnlf::spectral {

std::vector<double> torus_order_eigenvalues(double R, double r, int m, int fourier_modes) {
  require(R > r && r > 0, "torus_order_eigenvalues: need R > r > 0");
  const int nb = 2 * fourier_modes + 1, nq = 1024;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nb, nb), B = Eigen::MatrixXd::Zero(nb, nb);
  Eigen::VectorXd f(nb), df(nb);
  const double two_pi = 6.283185307179586, wq = two_pi / nq;
  for (int q = 0; q < nq; ++q) {
    const double th = two_pi * q / nq, rho = R + r * std::cos(th);
    f[0] = 1;
    df[0] = 0;
    for (int k = 1; k <= fourier_modes; ++k) {
      f[2 * k - 1] = std::cos(k * th);
      df[2 * k - 1] = -k * std::sin(k * th);
      f[2 * k] = std::sin(k * th);
      df[2 * k] = k * std::cos(k * th);
    }
    // Weak form: ∫ ρ g' h' + m² r²/ρ g h dθ = λ r² ∫ ρ g h dθ.
    A.noalias() += wq * (rho * df * df.transpose() + (m * m * r * r / rho) * f * f.transpose());
    B.noalias() += wq * (r * r * rho) * f * f.transpose();
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(A, B);
  require(es.info() == Eigen::Success, "torus_order_eigenvalues: eigensolver failed");
  std::vector<double> v(es.eigenvalues().data(), es.eigenvalues().data() + nb);
  std::sort(v.begin(), v.end());
  return v;
}

std::vector<double> torus_eigenvalues(double R, double r, int count) {
  std::vector<double> all;
  // Order m's eigenvalues are ≥ m²/(R + r)² (Rayleigh quotient of the φ part), so the orders
  // beyond the current count-th value cannot contribute.
  for (int m = 0;; ++m) {
    if (int(all.size()) >= count + 1) {
      std::vector<double> s = all;
      std::sort(s.begin(), s.end());
      if (m * m / ((R + r) * (R + r)) > s[count]) break;
    }
    const auto v = torus_order_eigenvalues(R, r, m);
    // Keep the well-resolved lower half of the Galerkin spectrum.
    for (size_t i = 0; i < v.size() / 2; ++i) {
      if (m == 0 && i == 0) continue;  // the constant mode
      all.push_back(v[i]);
      if (m > 0) all.push_back(v[i]);
    }
  }
  std::sort(all.begin(), all.end());
  all.resize(count);
  return all;
}

}  // namespace sgnlf::spectral
