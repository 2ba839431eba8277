// Spectral-geometric fusion: device vs host reference (forward, backward), finite differences of
// the backward, the λ ramp, and λ = 0 leaving the density MLP's output unchanged vs no fusion.
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "field/mlp.hpp"
#include "spectral/fusion.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::spectral;

namespace {

std::vector<float> random_vec(size_t n, uint64_t seed) {
  Rng r(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = r.uniform(-1, 1);
  return v;
}

// Host reference (tests only).
std::vector<float> fusion_ref(const std::vector<float>& geo, const std::vector<float>& psi, int n, int g, int k,
                              float lambda) {
  std::vector<float> out(size_t(n) * (g + k));
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < g; ++c) out[size_t(i) * (g + k) + c] = geo[size_t(i) * g + c];
    for (int c = 0; c < k; ++c) out[size_t(i) * (g + k) + g + c] = lambda * psi[size_t(i) * k + c];
  }
  return out;
}

}  // namespace

TEST_CASE("fusion forward and backward match the host reference", "[fusion]") {
  auto& rt = test::runtime();
  const int n = 1003, g = 32, k = 16;
  const float lambda = 0.37f;
  SpectralFusion fusion(rt, g, k);
  REQUIRE(fusion.fusion_width() == g + k);
  const auto geo = random_vec(size_t(n) * g, 1), psi = random_vec(size_t(n) * k, 2);
  auto bgeo = cl::Buffer::from(rt, geo), bpsi = cl::Buffer::from(rt, psi);
  cl::Buffer hyb(rt, size_t(n) * (g + k) * sizeof(float));
  fusion.forward(bgeo, bpsi, n, lambda, hyb);
  // Bit equality, exact by construction on any device: a copy and one IEEE multiplication.
  CHECK(test::max_abs_err(hyb.read_vec<float>(size_t(n) * (g + k)), fusion_ref(geo, psi, n, g, k, lambda)) == 0);

  // Backward against finite differences of the scalar L = <d_hyb, f_hyb(geo, psi)>.
  const auto d_hyb = random_vec(size_t(n) * (g + k), 3);
  auto bd = cl::Buffer::from(rt, d_hyb);
  cl::Buffer d_geo(rt, size_t(n) * g * sizeof(float)), d_psi(rt, size_t(n) * k * sizeof(float));
  fusion.backward(bd, n, lambda, &d_geo, d_psi);
  const auto dg = d_geo.read_vec<float>(size_t(n) * g), dp = d_psi.read_vec<float>(size_t(n) * k);
  auto loss = [&](const std::vector<float>& ge, const std::vector<float>& ps) {
    const auto h = fusion_ref(ge, ps, n, g, k, lambda);
    double s = 0;
    for (size_t i = 0; i < h.size(); ++i) s += double(h[i]) * d_hyb[i];
    return s;
  };
  Rng rng(4);
  for (int t = 0; t < 50; ++t) {
    auto ge = geo;
    auto ps = psi;
    const size_t i = rng.below(uint32_t(ge.size())), j = rng.below(uint32_t(ps.size()));
    const float e = 1e-2f;
    ge[i] += e;
    const double fd_g = (loss(ge, psi) - loss(geo, psi)) / e;
    ps[j] += e;
    const double fd_p = (loss(geo, ps) - loss(geo, psi)) / e;
    CHECK(std::fabs(fd_g - dg[i]) < 1e-4);
    CHECK(std::fabs(fd_p - dp[j]) < 1e-4);
  }
  // Without d_geo only d_psi is written, the same bits (same kernel, same device).
  d_psi.fill_zero();
  fusion.backward(bd, n, lambda, nullptr, d_psi);
  CHECK(test::max_abs_err(d_psi.read_vec<float>(size_t(n) * k), dp) == 0);
}

TEST_CASE("fusion ramp goes 0 -> 1 over its window", "[fusion]") {
  FusionRamp r{100, 300};
  CHECK(r.lambda(0) == 0);
  CHECK(r.lambda(100) == 0);
  CHECK(r.lambda(200) == Approx(0.5));
  CHECK(r.lambda(300) == 1);
  CHECK(r.lambda(10000) == 1);
  FusionRamp step{50, 50};
  CHECK(step.lambda(49) == 0);
  CHECK(step.lambda(50) == 1);
  CHECK_THROWS_AS((FusionRamp{10, 5}.validate()), ConfigError);
}

TEST_CASE("with lambda = 0 the density MLP behaves exactly as without fusion", "[fusion]") {
  auto& rt = test::runtime();
  const int n = 777, g = 32, k = 16;
  using field::Activation;
  field::Mlp plain(rt, field::make_mlp_spec(g, 64, 1, 16, Activation::Relu));
  field::Mlp fused(rt, field::make_mlp_spec(g + k, 64, 1, 16, Activation::Relu));
  std::vector<float> p_plain(plain.n_params()), p_fused(fused.n_params());
  plain.init_params(p_plain, 0, 5);
  fused.init_params(p_fused, 0, 6);  // the K extra input rows stay random (non-zero)
  // Same weights for the geometric inputs: layer 0 is W_t[n_in][64] then b[64].
  for (int i = 0; i < g; ++i)
    for (int o = 0; o < 64; ++o) p_fused[size_t(i) * 64 + o] = p_plain[size_t(i) * 64 + o];
  for (int o = 0; o < 64; ++o) p_fused[size_t(g + k) * 64 + o] = p_plain[size_t(g) * 64 + o];
  const size_t rest = plain.n_params() - plain.layer_offset(1);
  std::copy_n(p_plain.begin() + plain.layer_offset(1), rest, p_fused.begin() + fused.layer_offset(1));

  const auto geo = random_vec(size_t(n) * g, 7), psi = random_vec(size_t(n) * k, 8);
  auto bgeo = cl::Buffer::from(rt, geo), bpsi = cl::Buffer::from(rt, psi);
  auto bp_plain = cl::Buffer::from(rt, p_plain), bp_fused = cl::Buffer::from(rt, p_fused);
  SpectralFusion fusion(rt, g, k);
  cl::Buffer hyb(rt, size_t(n) * (g + k) * 4), out_plain(rt, size_t(n) * 16 * 4), out_fused(rt, size_t(n) * 16 * 4);
  field::MlpContext c1, c2;
  plain.forward(bp_plain, 0, bgeo, n, out_plain, c1);
  fusion.forward(bgeo, bpsi, n, 0.0f, hyb);
  fused.forward(bp_fused, 0, hyb, n, out_fused, c2);
  const auto h = hyb.read_vec<float>(size_t(n) * (g + k));
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < g; ++c) REQUIRE(h[size_t(i) * (g + k) + c] == geo[size_t(i) * g + c]);
  const auto a = out_plain.read_vec<float>(size_t(n) * 16), b = out_fused.read_vec<float>(size_t(n) * 16);
  CHECK(test::max_sym_rel_err(a, b) < 1e-6);
  // And Ψ receives no gradient through the fusion at λ = 0.
  auto d_hyb = cl::Buffer::from(rt, random_vec(size_t(n) * (g + k), 9));
  cl::Buffer d_psi(rt, size_t(n) * k * 4);
  fusion.backward(d_hyb, n, 0.0f, nullptr, d_psi);
  for (float v : d_psi.read_vec<float>(size_t(n) * k)) REQUIRE(v == 0.0f);
  // The check can fail: λ = 1 changes the output.
  fusion.forward(bgeo, bpsi, n, 1.0f, hyb);
  fused.forward(bp_fused, 0, hyb, n, out_fused, c2);
  CHECK(test::max_sym_rel_err(a, out_fused.read_vec<float>(size_t(n) * 16)) > 1e-3);
}
