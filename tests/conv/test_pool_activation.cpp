// Leaky ReLU and 2×2 average pooling: device vs host reference, finite differences of the device
// forward, accumulation, untouched padding channels, shape errors.
#include <catch2/catch.hpp>

#include <cmath>

#include "conv/avg_pool.hpp"
#include "conv/leaky_relu.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
using test::uniform;
double dot(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += double(a[i]) * b[i];
  return s;
}
}  // namespace

TEST_CASE("Leaky ReLU matches the reference and finite differences", "[conv][leaky_relu]") {
  auto& rt = test::runtime();
  const float slope = 0.2f;
  conv::LeakyRelu act(rt, slope);
  for (size_t n : {size_t(16 * 37), size_t(16 * 5 + 7)}) {  // whole vectors and a tail
    auto x = uniform(n, -1.0f, 1.0f, 1);
    for (auto& v : x)
      if (std::fabs(v) < 0.05f) v = 0.3f;  // keep finite differences off the kink
    const auto dy = uniform(n, -1.0f, 1.0f, 2);
    auto b_x = cl::Buffer::from(rt, x), b_dy = cl::Buffer::from(rt, dy);
    cl::Buffer b_y(rt, n * 4), b_dx(rt, n * 4);
    act.forward(b_x, n, b_y);
    act.backward(b_x, b_dy, n, b_dx);
    const auto y = b_y.read_all<float>(), dx = b_dx.read_all<float>();
    // Bit equality, exact by construction: a selection of x or one IEEE multiplication.
    CHECK(y == test::ref::leaky_relu_fwd(x, slope));
    CHECK(dx == test::ref::leaky_relu_bwd(x, dy, slope));
    // FD of L = Σ dy · f(x) through the device forward, every 7th entry.
    std::vector<float> fd, an;
    const float h = 1e-2f;
    for (size_t k = 0; k < n; k += 7) {
      auto xp = x, xm = x;
      xp[k] += h;
      xm[k] -= h;
      b_x.write_vec(xp);
      act.forward(b_x, n, b_y);
      const double lp = dot(b_y.read_all<float>(), dy);
      b_x.write_vec(xm);
      act.forward(b_x, n, b_y);
      const double lm = dot(b_y.read_all<float>(), dy);
      fd.push_back(float((lp - lm) / (2.0 * h)));
      an.push_back(dx[k]);
    }
    CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 1e-3);
  }
  REQUIRE_THROWS_WITH(conv::LeakyRelu(rt, -0.1f), Catch::Contains("'slope' = -0.1"));
}

TEST_CASE("2x2 average pooling matches the reference and finite differences", "[conv][pool]") {
  auto& rt = test::runtime();
  conv::AvgPool2x2 pool(rt);
  // Odd sizes (the last row and column are dropped), a strided output, a padded input.
  for (const conv::PoolShape s : {conv::PoolShape{2, 9, 13, 2, 2, 2}, conv::PoolShape{1, 8, 6, 3, 4, 5}}) {
    const auto in = uniform(size_t(s.n) * s.h * s.w * s.in_cs, -1.0f, 1.0f, 3);
    const size_t out_n = size_t(s.n) * s.out_h() * s.out_w() * s.out_cs;
    const std::vector<float> out0(out_n, 5.0f);
    const auto d_out = uniform(out_n, -1.0f, 1.0f, 4);
    const auto d_in0 = uniform(in.size(), -1.0f, 1.0f, 5);
    auto b_in = cl::Buffer::from(rt, in), b_out = cl::Buffer::from(rt, out0);
    auto b_dout = cl::Buffer::from(rt, d_out), b_din = cl::Buffer::from(rt, d_in0);
    pool.forward(s, b_in, b_out);
    const auto out = b_out.read_all<float>();
    // Bit equality, exact by construction: additions in the kernel's order and scaling by 0.25
    // (a power of two: exact, so also the accumulating backward's 0.25·d + d_in, fused or not).
    CHECK(out == test::ref::avgpool2_fwd(s, in, out0));
    for (bool acc : {false, true}) {
      b_din.write_vec(d_in0);
      pool.backward(s, b_dout, b_din, acc);
      CHECK(b_din.read_all<float>() == test::ref::avgpool2_bwd(s, d_out, d_in0, acc));
    }
    // FD of L = Σ d_out · pool(in) on the pooled channels.
    pool.backward(s, b_dout, b_din, false);
    const auto din = b_din.read_all<float>();
    std::vector<float> fd, an;
    const float h = 1e-2f;
    auto loss = [&](const std::vector<float>& x) {
      b_in.write_vec(x);
      pool.forward(s, b_in, b_out);
      auto o = b_out.read_all<float>();
      double l = 0;
      for (size_t i = 0; i < o.size(); ++i)
        if (int(i % size_t(s.out_cs)) < s.c) l += double(o[i]) * d_out[i];
      return l;
    };
    for (size_t k = 0; k < in.size(); k += 3) {
      if (int(k % size_t(s.in_cs)) >= s.c) continue;
      auto xp = in, xm = in;
      xp[k] += h;
      xm[k] -= h;
      fd.push_back(float((loss(xp) - loss(xm)) / (2.0 * h)));
      an.push_back(din[k]);
    }
    REQUIRE(fd.size() > 20);
    CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 1e-3);
  }
  cl::Buffer b(rt, 64);
  REQUIRE_THROWS_WITH(pool.forward(conv::PoolShape{1, 1, 4, 1, 1, 1}, b, b),
                      Catch::Contains("h = 1"));
}
