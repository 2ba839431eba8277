// Numerical reference spectrum of −Δ_S on a torus of revolution (major radius R, tube radius r),
// which has no closed form. With ρ(θ) = R + r cos θ (θ poloidal, φ toroidal) the metric is
// ds² = r² dθ² + ρ² dφ², and f = g(θ) e^{imφ} separates into one periodic Sturm–Liouville
// problem per toroidal order m:
//     −(ρ g')' + (m² r² / ρ) g = λ r² ρ g.
// It is solved by a Fourier–Galerkin method in θ (real basis 1, cos kθ, sin kθ, k ≤ 32,
// trapezoid quadrature with 1024 nodes, exact for the smooth periodic integrands up to round-off),
// giving spectrally accurate eigenvalues (m ≥ 1 counted twice: e^{±imφ}).
#pragma once
#include <vector>

namespace sgnlf::spectral {

// Eigenvalues of the order-m problem, ascending (each counted once).
std::vector<double> torus_order_eigenvalues(double R, double r, int m, int fourier_modes = 32);

// The smallest `count` non-zero eigenvalues of the torus with multiplicity, ascending.
std::vector<double> torus_eigenvalues(double R, double r, int count);

}  // namespace sgnlf::spectral
