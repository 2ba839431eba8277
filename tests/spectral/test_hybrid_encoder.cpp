// SG-NLF's hybrid encoder (spectral/hybrid_encoder.hpp): device vs the host references of its
// parts (hash grid, Ψ MLP, fusion), its dL/dx against finite differences and the reference, λ = 0
// reproducing the plain hash grid exactly, the range loss never reaching Ψ's weights, spectral
// steps lowering L_spe, and Ψ's checkpoint state round trip.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "field/adam.hpp"
#include "field/hash_grid_encoder.hpp"
#include "reference.hpp"
#include "spectral/hybrid_encoder.hpp"
#include "spectral/surface.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using namespace sgnlf::spectral;

namespace {

field::HashGridConfig small_grid() {
  field::HashGridConfig g;
  g.levels = 4;
  g.features = 2;
  g.log2_table_size = 12;
  g.base_resolution = 4;
  g.per_level_scale = 1.5f;
  g.deterministic = true;
  return g;
}

PsiSpec small_psi() {
  PsiSpec p;
  p.k = 6;
  p.width = 32;
  return p;
}

std::vector<float> random_vec(size_t n, uint64_t seed, float lo, float hi) {
  Rng r(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = r.uniform(lo, hi);
  return v;
}

// Host reference of the forward: [grid(x), λ·Ψ(x)].
std::vector<float> hybrid_ref(const field::HashGridConfig& g, const std::vector<float>& table,
                              const field::MlpSpec& psi_spec, const std::vector<float>& psi_params,
                              const std::vector<float>& x, int n, float lambda) {
  const std::vector<float> ones(size_t(g.levels), 1.0f);
  const auto geo = test::ref::hashgrid_fwd(g, table, x, ones);
  const auto psi = test::ref::mlp_fwd(psi_spec, psi_params, x, n);
  const int G = g.levels * g.features, K = psi_spec.layers.back().width;
  std::vector<float> out(size_t(n) * size_t(G + K));
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < G; ++c) out[size_t(i) * (G + K) + c] = geo[size_t(i) * G + c];
    for (int c = 0; c < K; ++c) out[size_t(i) * (G + K) + G + c] = lambda * psi[size_t(i) * K + c];
  }
  return out;
}

struct Setup {
  cl::Runtime& rt = test::runtime();
  field::HashGridConfig g = small_grid();
  HybridEncoder enc{rt, g, small_psi(), SpectralLossConfig{}};
  std::vector<float> host;
  cl::Buffer params;
  Setup() : host(enc.n_params()), params(rt, enc.n_params() * 4) {
    enc.init_params(host, 0, 7);
    // Larger table values than the ±1e-4 init so that the grid's share of dL/dx is visible.
    Rng r(11);
    for (auto& v : host) v = r.uniform(-0.5f, 0.5f);
    params.write_vec(host);
  }
};

}  // namespace

TEST_CASE("hybrid encoder forward matches the host reference", "[hybrid]") {
  Setup s;
  const int n = 517;
  const auto x = random_vec(size_t(n) * 3, 3, -0.9f, 0.9f);
  cl::Buffer xb(s.rt, x.size() * 4), enc(s.rt, size_t(n) * s.enc.width() * 4);
  xb.write_vec(x);
  for (float lambda : {0.0f, 0.4f, 1.0f}) {
    s.enc.set_lambda(lambda);
    s.enc.forward(s.params, 0, xb, n, enc);
    const auto got = enc.read_vec<float>(size_t(n) * s.enc.width());
    const auto want = hybrid_ref(s.g, s.host, psi_mlp_spec(small_psi()), s.enc.read_psi(),
                                 x, n, lambda);
    double worst = 0;
    for (size_t i = 0; i < got.size(); ++i) worst = std::max(worst, double(std::abs(got[i] - want[i])));
    INFO("lambda " << lambda);
    CHECK(worst < 2e-5);
  }
}

TEST_CASE("hybrid encoder dL/dx matches the reference and finite differences", "[hybrid]") {
  Setup s;
  const int n = 64;
  const float lambda = 0.8f;
  const int W = s.enc.width(), G = s.g.levels * s.g.features, K = small_psi().k;
  const auto x = random_vec(size_t(n) * 3, 5, -0.8f, 0.8f);
  const auto d_enc = random_vec(size_t(n) * W, 9, -1.0f, 1.0f);
  cl::Buffer xb(s.rt, x.size() * 4), enc(s.rt, size_t(n) * W * 4), denc(s.rt, d_enc.size() * 4),
      grad(s.rt, s.enc.n_params() * 4), dx(s.rt, x.size() * 4);
  xb.write_vec(x);
  denc.write_vec(d_enc);
  s.enc.set_lambda(lambda);
  const auto psi_before = s.enc.read_psi();
  const auto psi_grad_before = s.enc.psi_grad().read_vec<float>(s.enc.psi_params());
  s.enc.forward(s.params, 0, xb, n, enc);
  s.enc.backward(s.params, 0, xb, n, denc, grad, 0, &dx);
  const auto got = dx.read_vec<float>(x.size());

  // Reference: grid share from the geometric columns, Ψ share from λ·(Ψ columns).
  std::vector<float> d_geo(size_t(n) * G), d_psi(size_t(n) * K);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < G; ++c) d_geo[size_t(i) * G + c] = d_enc[size_t(i) * W + c];
    for (int c = 0; c < K; ++c) d_psi[size_t(i) * K + c] = lambda * d_enc[size_t(i) * W + G + c];
  }
  const std::vector<float> ones(size_t(s.g.levels), 1.0f);
  auto want = test::ref::hashgrid_bwd_dx(s.g, s.host, x, ones, d_geo);
  std::vector<float> d_in;
  test::ref::mlp_bwd(psi_mlp_spec(small_psi()), psi_before, x, n, d_psi, d_in);
  for (size_t i = 0; i < want.size(); ++i) want[i] += d_in[i];
  double worst = 0, scale = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    worst = std::max(worst, double(std::abs(got[i] - want[i])));
    scale = std::max(scale, double(std::abs(want[i])));
  }
  CHECK(worst < 1e-4 * std::max(1.0, scale));

  // Finite differences of L = Σ d_enc · enc(x) in double from the reference forward.
  auto loss = [&](const std::vector<float>& xs) {
    const auto e = hybrid_ref(s.g, s.host, psi_mlp_spec(small_psi()), psi_before, xs, n, lambda);
    double l = 0;
    for (size_t i = 0; i < e.size(); ++i) l += double(d_enc[i]) * e[i];
    return l;
  };
  const float eps = 1e-3f;
  int checked = 0, ok = 0;
  for (int i = 0; i < n; i += 5)
    for (int a = 0; a < 3; ++a) {
      auto xp = x, xm = x;
      xp[size_t(i) * 3 + a] += eps;
      xm[size_t(i) * 3 + a] -= eps;
      const double fd = (loss(xp) - loss(xm)) / (2.0 * eps);
      const double an = got[size_t(i) * 3 + a];
      ++checked;
      if (std::abs(fd - an) <= 2e-2 * std::max(1.0, std::abs(fd))) ++ok;
    }
  // The hash grid is piecewise trilinear: a difference straddling a cell boundary may differ.
  CHECK(ok >= checked * 9 / 10);

  // The range loss never reaches Ψ's weights nor the gradient its optimiser steps on.
  CHECK(s.enc.read_psi() == psi_before);
  CHECK(s.enc.psi_grad().read_vec<float>(s.enc.psi_params()) == psi_grad_before);
}

TEST_CASE("hybrid encoder at lambda 0 is the hash grid exactly", "[hybrid]") {
  Setup s;
  field::HashGridEncoder plain(s.rt, s.g);
  const int n = 300, W = s.enc.width(), G = plain.width();
  const auto x = random_vec(size_t(n) * 3, 13, -1.0f, 1.0f);
  const auto d_enc = random_vec(size_t(n) * W, 17, -1.0f, 1.0f);
  std::vector<float> d_geo(size_t(n) * G);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < G; ++c) d_geo[size_t(i) * G + c] = d_enc[size_t(i) * W + c];
  cl::Buffer xb(s.rt, x.size() * 4), e1(s.rt, size_t(n) * W * 4), e2(s.rt, size_t(n) * G * 4),
      d1(s.rt, d_enc.size() * 4), d2(s.rt, d_geo.size() * 4), g1(s.rt, s.enc.n_params() * 4),
      g2(s.rt, plain.n_params() * 4), x1(s.rt, x.size() * 4), x2(s.rt, x.size() * 4);
  xb.write_vec(x);
  d1.write_vec(d_enc);
  d2.write_vec(d_geo);
  s.enc.set_lambda(0.0f);
  s.enc.forward(s.params, 0, xb, n, e1);
  plain.forward(s.params, 0, xb, n, e2);
  s.enc.backward(s.params, 0, xb, n, d1, g1, 0, &x1);
  plain.backward(s.params, 0, xb, n, d2, g2, 0, &x2);
  const auto a = e1.read_vec<float>(size_t(n) * W), b = e2.read_vec<float>(size_t(n) * G);
  bool same = true, zero = true;
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < G; ++c) same = same && a[size_t(i) * W + c] == b[size_t(i) * G + c];
    for (int c = G; c < W; ++c) zero = zero && a[size_t(i) * W + c] == 0.0f;
  }
  CHECK(same);
  CHECK(zero);
  CHECK(g1.read_vec<float>(s.enc.n_params()) == g2.read_vec<float>(plain.n_params()));
  CHECK(x1.read_vec<float>(x.size()) == x2.read_vec<float>(x.size()));
}

TEST_CASE("hybrid encoder without the grid is lambda times Psi, forward and dL/dx", "[hybrid]") {
  // The ablation "spectral only" (method.md §5): no hash grid, f = λ·Ψ(x).
  cl::Runtime& rt = test::runtime();
  HybridEncoder enc(rt, small_grid(), small_psi(), SpectralLossConfig{}, /*geometric=*/false);
  const int n = 96, K = small_psi().k;
  CHECK(enc.width() == K);
  CHECK(enc.parts() == std::vector<int>{K});
  CHECK(enc.n_params() == 0);
  std::vector<float> host;  // no parameters of its own
  enc.init_params(host, 0, 7);
  CHECK(host.empty());
  const auto psi = enc.read_psi();
  const auto x = random_vec(size_t(n) * 3, 23, -0.8f, 0.8f);
  const auto d_enc = random_vec(size_t(n) * K, 29, -1.0f, 1.0f);
  cl::Buffer params(rt, 4), xb(rt, x.size() * 4), e(rt, size_t(n) * K * 4), d(rt, d_enc.size() * 4),
      grad(rt, 4), dx(rt, x.size() * 4);
  xb.write_vec(x);
  d.write_vec(d_enc);
  const auto spec = psi_mlp_spec(small_psi());
  const auto ref = test::ref::mlp_fwd(spec, psi, x, n);
  auto loss = [&](const std::vector<float>& xs, float lambda) {
    const auto p = test::ref::mlp_fwd(spec, psi, xs, n);
    double l = 0;
    for (size_t i = 0; i < p.size(); ++i) l += double(d_enc[i]) * lambda * p[i];
    return l;
  };
  for (float lambda : {1.0f, 0.3f}) {
    INFO("lambda " << lambda);
    enc.set_lambda(lambda);
    enc.forward(params, 0, xb, n, e);
    const auto got = e.read_vec<float>(size_t(n) * K);
    double worst = 0;
    for (size_t i = 0; i < got.size(); ++i)
      worst = std::max(worst, double(std::abs(got[i] - lambda * ref[i])));
    CHECK(worst < 2e-5);
    enc.backward(params, 0, xb, n, d, grad, 0, &dx);
    const auto g = dx.read_vec<float>(x.size());
    std::vector<float> d_psi(d_enc.size()), want;
    for (size_t i = 0; i < d_enc.size(); ++i) d_psi[i] = lambda * d_enc[i];
    test::ref::mlp_bwd(spec, psi, x, n, d_psi, want);
    double worst_dx = 0, fd_worst = 0;
    for (size_t i = 0; i < g.size(); ++i) worst_dx = std::max(worst_dx, double(std::abs(g[i] - want[i])));
    CHECK(worst_dx < 1e-4);
    const float eps = 1e-3f;  // Ψ is smooth (tanh): central differences agree everywhere
    for (int i = 0; i < n; i += 7)
      for (int a = 0; a < 3; ++a) {
        auto xp = x, xm = x;
        xp[size_t(i) * 3 + a] += eps;
        xm[size_t(i) * 3 + a] -= eps;
        const double fd = (loss(xp, lambda) - loss(xm, lambda)) / (2.0 * eps);
        fd_worst = std::max(fd_worst, std::abs(fd - g[size_t(i) * 3 + a]) / std::max(1.0, std::abs(fd)));
      }
    CHECK(fd_worst < 1e-2);
  }
  // λ = 0: nothing depends on x, and the gradient says so (after a λ > 0 pass wrote one).
  enc.set_lambda(0.0f);
  enc.forward(params, 0, xb, n, e);
  for (float v : e.read_vec<float>(size_t(n) * K)) REQUIRE(v == 0.0f);
  enc.backward(params, 0, xb, n, d, grad, 0, &dx);
  for (float v : dx.read_vec<float>(x.size())) REQUIRE(v == 0.0f);
  CHECK(enc.read_psi() == psi);  // the range loss never trains Ψ
}

TEST_CASE("hybrid encoder spectral steps lower the spectral loss on a sphere", "[hybrid]") {
  Setup s;
  Rng rng(21, 3);
  ShapeSpec sphere = ShapeSpec::preset(ShapeKind::sphere);
  sphere.radius = 0.6;
  const auto shape = make_shape(sphere);
  auto batch = [&]() {
    auto pts = shape->sample(rng, 512);
    for (auto& p : pts) p.w = 1.0 / 512.0;
    return pts;
  };
  const auto fixed = batch();
  // Ψ's optimiser is its loss term's (pipeline::SpectralLoss); here an Adam of the test's.
  field::Adam adam(s.rt, s.enc.psi_params());
  const auto step = [&](const std::vector<spectral::SurfacePoint>& b, float lr) {
    const double l = s.enc.spectral_gradient(b);
    adam.begin_step();
    adam.update(s.enc.psi_param_buffer(), s.enc.psi_grad(), 0, s.enc.psi_params(), lr);
    return l;
  };
  double first = 0, last = 0;
  for (int i = 0; i < 150; ++i) {
    const double l = step(batch(), 1e-2f);
    REQUIRE(std::isfinite(l));
    if (i == 0) first = l;
  }
  last = step(fixed, 0.0f);
  // The minimum of tr(S⁻¹P) is the sum of the first K = 6 non-zero eigenvalues of the sphere:
  // 3 × 2/r² + 3 × 6/r² (r = 0.6) = 66.7. The random start is ~10 % above it.
  const double optimum = (3 * 2.0 + 3 * 6.0) / (0.6 * 0.6);
  INFO("first " << first << " last " << last << " optimum " << optimum);
  CHECK(first > 1.05 * optimum);
  CHECK(last < 1.03 * optimum);
}

TEST_CASE("hybrid encoder state round trip and bad lambda", "[hybrid]") {
  Setup s;
  auto st = s.enc.read_psi();
  for (auto& v : st) v *= 0.5f;
  s.enc.write_psi(st);
  CHECK(s.enc.read_psi() == st);
  st.pop_back();
  CHECK_THROWS_AS(s.enc.write_psi(st), IoError);
  CHECK_THROWS(s.enc.set_lambda(1.5f));
  CHECK_THROWS(s.enc.set_lambda(std::nanf("")));
}
