// Fusion launcher and λ ramp (fusion.hpp).
#include "spectral/fusion.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"

namespace sgnlf::spectral {

SpectralFusion::SpectralFusion(cl::Runtime& rt, int geo_width, int k) : geo_width_(geo_width), k_(k) {
  require(geo_width >= 0 && k >= 1, "SpectralFusion: need geo_width >= 0 and k >= 1");
  const std::string opt = "-DFUSION_G=" + std::to_string(geo_width) + " -DFUSION_K=" + std::to_string(k);
  fwd_ = rt.kernel("spectral/fusion.cl", "spectral_fusion_fwd", opt);
  bwd_ = rt.kernel("spectral/fusion.cl", "spectral_fusion_bwd", opt);
}

namespace {
void check(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("SpectralFusion: buffer '") + what + "' too small (" + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(floats * sizeof(float)) + ")");
}
}  // namespace

void SpectralFusion::forward(const cl::Buffer& geo, const cl::Buffer& psi, int n, float lambda, cl::Buffer& hyb) {
  if (n <= 0) return;
  if (geo_width_ > 0) check(geo, size_t(n) * geo_width_, "geo");
  check(psi, size_t(n) * k_, "psi");
  check(hyb, size_t(n) * fusion_width(), "hyb");
  fwd_.set_args(n, lambda, geo_width_ > 0 ? geo : psi, psi, hyb);
  fwd_.launch({cl::round_up(size_t(n) * fusion_width(), 64)}, {64});
}

void SpectralFusion::backward(const cl::Buffer& d_hyb, int n, float lambda, cl::Buffer* d_geo, cl::Buffer& d_psi) {
  if (n <= 0) return;
  check(d_hyb, size_t(n) * fusion_width(), "d_hyb");
  check(d_psi, size_t(n) * k_, "d_psi");
  if (d_geo) check(*d_geo, size_t(n) * geo_width_, "d_geo");
  bwd_.set_args(n, lambda, int(d_geo != nullptr), d_hyb, d_geo ? *d_geo : d_psi, d_psi);
  bwd_.launch({cl::round_up(size_t(n) * fusion_width(), 64)}, {64});
}

}  // namespace sgnlf::spectral
