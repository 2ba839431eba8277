// Random-Fourier-feature stand-in for f_hyb (see standin_features.hpp).
#include "posegraph/standin_features.hpp"

#include <cmath>
#include <memory>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::posegraph {

void StandinFeatureConfig::validate() const {
  check_range("stand-in features", "frequencies", frequencies, 1, 4096);
  check_range("stand-in features", "min_wavelength_m", min_wavelength_m, 1e-3, 1e6);
  check_range("stand-in features", "max_wavelength_m", max_wavelength_m, min_wavelength_m, 1e6);
}

FeatureProvider standin_fourier_features(const StandinFeatureConfig& c) {
  c.validate();
  // Angular wave vectors 2π w_k / λ_k, drawn once.
  auto waves = std::make_shared<std::vector<Eigen::Vector3d>>();
  Rng rng(c.seed, 0x5741u);
  const double log_lo = std::log(c.min_wavelength_m), log_hi = std::log(c.max_wavelength_m);
  for (int k = 0; k < c.frequencies; ++k) {
    Eigen::Vector3d w;
    do {
      const double z = rng.normal(), y = rng.normal(), x = rng.normal();  // z first: GCC's order (core/rng.hpp)
      w = Eigen::Vector3d(x, y, z);
    } while (w.norm() < 1e-6);
    const double lambda = std::exp(log_lo + (log_hi - log_lo) * rng.uniform_double());
    waves->push_back(w.normalized() * (2.0 * M_PI / lambda));
  }
  const int F = c.frequencies;
  FeatureProvider p;
  p.dim = 2 * F;
  p.name = "stand-in: random Fourier features of x_world (" + std::to_string(F) +
           " waves, wavelengths " + std::to_string(c.min_wavelength_m) + "-" +
           std::to_string(c.max_wavelength_m) + " m, seed " + std::to_string(c.seed) + ")";
  p.eval = [waves, F](const std::vector<Eigen::Vector3f>& x, std::vector<float>& out) {
    const double s = 1.0 / std::sqrt(double(F));
    out.resize(x.size() * size_t(2 * F));
    for (size_t r = 0; r < x.size(); ++r) {
      const Eigen::Vector3d xd = x[r].cast<double>();
      float* row = out.data() + r * size_t(2 * F);
      for (int k = 0; k < F; ++k) {
        const double a = (*waves)[size_t(k)].dot(xd);
        row[2 * k] = float(s * std::cos(a));
        row[2 * k + 1] = float(s * std::sin(a));
      }
    }
  };
  return p;
}

}  // namespace sgnlf::posegraph
