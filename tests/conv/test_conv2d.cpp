// Conv2d: device vs host reference (forward, dL/dparams, dL/dinput) for the PatchGAN's layer
// shapes (4×4, stride 2 and 1) and U-Net-like 3×3 shapes, odd sizes and channel counts, several
// weight-gradient chunks; finite differences of the device forward; shape errors.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "conv/conv2d.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
using test::uniform;
using test::norm_err;  // float sums against a double reference scale with the output
// Zeroes the padding channels c.. of an NHWC buffer with channel stride cs.
void zero_padding(std::vector<float>& v, int c, int cs) {
  for (size_t i = 0; i < v.size(); ++i)
    if (int(i % size_t(cs)) >= c) v[i] = 0.0f;
}
struct Case {
  const char* name;
  conv::Conv2dSpec spec;
  int n, h, w;
};
conv::Conv2dSpec spec(int ci, int co, int k, int s, int p, int in_cs = 0) {
  conv::Conv2dSpec c;
  c.c_in = ci;
  c.c_out = co;
  c.kernel = k;
  c.stride = s;
  c.pad = p;
  c.in_cs = in_cs;
  return c;
}
}  // namespace

TEST_CASE("Conv2d forward and backward match the host reference", "[conv][conv2d]") {
  auto& rt = test::runtime();
  const std::vector<Case> cases = {
      {"patchgan 2->32 k4 s2", spec(2, 32, 4, 2, 1), 2, 17, 45},
      {"patchgan 32->64 k4 s2", spec(32, 64, 4, 2, 1), 2, 9, 23},
      {"patchgan 64->128 k4 s1", spec(64, 128, 4, 1, 1), 1, 6, 13},
      {"patchgan 128->1 k4 s1", spec(128, 1, 4, 1, 1), 2, 5, 12},
      {"unet 16->16 k3 s1", spec(16, 16, 3, 1, 1), 2, 7, 19},
      {"odd 5->20 k3 s2 in_cs 8", spec(5, 20, 3, 2, 1, 8), 3, 8, 11},
      {"odd 3->7 k4 s2 pad 0", spec(3, 7, 4, 2, 0), 1, 10, 21},
      {"many chunks 2->32 k4 s1", spec(2, 32, 4, 1, 1), 2, 41, 67},
      {"narrow 32->2 k3 s2", spec(32, 2, 3, 2, 1), 2, 9, 14},
      {"narrow 16->1 k3 s1 in_cs 32", spec(16, 1, 3, 1, 1, 32), 1, 7, 20},
  };
  for (const auto& c : cases) {
    SECTION(c.name) {
      conv::Conv2d cv(rt, c.spec);
      const auto& s = c.spec;
      // The narrow-output kernels serve c_out <= 2 with 16-aligned input channels (cpu_tiles;
      // local_tiles, the gpu profile's, has no narrow variants).
      const bool cpu = !cv.local_tiles();
      CHECK(cv.local_tiles() == (rt.device_profile().gemm == cl::GemmVariant::LocalTiles));
      CHECK(cv.narrow() == (cpu && s.c_out <= 2 && s.c_in % 16 == 0 && s.input_cs() % 16 == 0));
      CHECK(cv.narrow_input() == (cpu && s.c_in <= 4));
      const int ho = s.out_size(c.h), wo = s.out_size(c.w), ics = s.input_cs(), ocs = s.out_cs();
      const size_t off = 32;
      std::vector<float> params(off + cv.n_params(), 0.0f);
      cv.init_params(params, off, 3, 0.2f);
      for (int o = 0; o < s.c_out; ++o) params[off + s.bias_index(o)] = 0.05f * (o % 5 - 2);
      const std::vector<float> slice(params.begin() + off, params.end());
      auto in = uniform(size_t(c.n) * c.h * c.w * ics, -1.0f, 1.0f, 4);
      auto d_out = uniform(size_t(c.n) * ho * wo * ocs, -1.0f, 1.0f, 5);
      zero_padding(d_out, s.c_out, ocs);  // as the next layer's backward leaves it
      auto b_p = cl::Buffer::from(rt, params), b_in = cl::Buffer::from(rt, in);
      auto b_dout = cl::Buffer::from(rt, d_out);
      cl::Buffer b_out(rt, d_out.size() * 4);
      auto b_din = cl::Buffer::from(rt, std::vector<float>(in.size(), 7.0f));
      auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 9.0f));
      cv.forward(b_p, off, b_in, c.n, c.h, c.w, b_out);
      cv.backward(b_p, off, b_in, c.n, c.h, c.w, b_dout, &b_grad, off, &b_din);
      const auto out = b_out.read_all<float>();
      const auto grad = b_grad.read_all<float>();
      const auto din = b_din.read_all<float>();
      std::vector<float> din_ref;
      const auto out_ref = test::ref::conv2d_fwd(s, slice, in, c.n, c.h, c.w);
      const auto g_ref = test::ref::conv2d_bwd(s, slice, in, c.n, c.h, c.w, d_out, din_ref);
      const std::vector<float> g_dev(grad.begin() + off, grad.end());
      CHECK(norm_err(out, out_ref) < 1e-5);
      CHECK(norm_err(g_dev, g_ref) < 1e-5);
      CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 1e-4);
      // d_in: the c_in channels equal the reference, padding channels keep their old value.
      std::vector<float> din_ch, din_ref_ch;
      for (size_t i = 0; i < din.size(); ++i) {
        if (int(i % size_t(ics)) < s.c_in) {
          din_ch.push_back(din[i]);
          din_ref_ch.push_back(din_ref[i]);
        } else {
          CHECK(din[i] == 7.0f);
        }
      }
      CHECK(norm_err(din_ch, din_ref_ch) < 1e-5);
      CHECK(grad[off - 1] == 9.0f);  // outside the slice: untouched
      for (int o = s.c_out; o < ocs; ++o) CHECK(g_dev[s.bias_index(o)] == 0.0f);
      for (size_t i = 0; i < out.size(); ++i)
        if (int(i % size_t(ocs)) >= s.c_out) REQUIRE(out[i] == 0.0f);  // padding channels
      // Fused leaky ReLU: same pre-activation, activation of exactly that output (same kernel
      // and device; the activation is a selection or one multiplication: bit equality).
      cl::Buffer b_pre(rt, d_out.size() * 4), b_act(rt, d_out.size() * 4);
      cv.forward(b_p, off, b_in, c.n, c.h, c.w, b_pre, &b_act, 0.2f);
      CHECK(b_pre.read_all<float>() == out);
      CHECK(b_act.read_all<float>() == test::ref::leaky_relu_fwd(out, 0.2f));
    }
  }
}

TEST_CASE("Conv2d gradients agree with finite differences of the device forward",
          "[conv][conv2d][fd]") {
  auto& rt = test::runtime();
  for (const auto& s : {spec(3, 5, 3, 2, 1), spec(4, 6, 4, 1, 1), spec(2, 17, 4, 2, 1),
                        spec(16, 1, 4, 1, 1), spec(32, 2, 3, 2, 1)}) {
    conv::Conv2d cv(rt, s);
    const int n = 2, h = 7, w = 9, ho = s.out_size(h), wo = s.out_size(w);
    std::vector<float> params(cv.n_params(), 0.0f);
    cv.init_params(params, 0, 11, 0.3f);
    for (int o = 0; o < s.c_out; ++o) params[s.bias_index(o)] = 0.1f;
    const auto in = uniform(size_t(n) * h * w * s.input_cs(), -1.0f, 1.0f, 12);
    auto r = uniform(size_t(n) * ho * wo * s.out_cs(), -1.0f, 1.0f, 13);  // L = Σ r · out
    zero_padding(r, s.c_out, s.out_cs());
    auto b_p = cl::Buffer::from(rt, params), b_in = cl::Buffer::from(rt, in);
    auto b_r = cl::Buffer::from(rt, r);
    cl::Buffer b_out(rt, r.size() * 4), b_din(rt, in.size() * 4), b_g(rt, params.size() * 4);
    cv.backward(b_p, 0, b_in, n, h, w, b_r, &b_g, 0, &b_din);
    const auto grad = b_g.read_all<float>();
    const auto din = b_din.read_all<float>();
    auto loss = [&](const std::vector<float>& p, const std::vector<float>& x) {
      b_p.write_vec(p);
      b_in.write_vec(x);
      cv.forward(b_p, 0, b_in, n, h, w, b_out);
      const auto out = b_out.read_all<float>();
      double l = 0;
      for (size_t i = 0; i < out.size(); ++i) l += double(out[i]) * r[i];
      return l;
    };
    // Linear in both: central differences are exact up to float rounding of the output.
    const float step = 1e-2f;
    std::vector<float> fd, an;
    for (size_t k = 0; k < params.size(); k += 5) {
      if (grad[k] == 0.0f) continue;  // padding columns
      auto pp = params, pm = params;
      pp[k] += step;
      pm[k] -= step;
      fd.push_back(float((loss(pp, in) - loss(pm, in)) / (2.0 * step)));
      an.push_back(grad[k]);
    }
    REQUIRE(fd.size() > 20);
    CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 2e-3);
    fd.clear();
    an.clear();
    for (size_t k = 0; k < in.size(); k += 3) {
      auto xp = in, xm = in;
      xp[k] += step;
      xm[k] -= step;
      fd.push_back(float((loss(params, xp) - loss(params, xm)) / (2.0 * step)));
      an.push_back(din[k]);
    }
    CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 2e-3);
  }
}

TEST_CASE("Conv2d rejects bad specs and shapes with the bad value", "[conv][conv2d]") {
  auto& rt = test::runtime();
  REQUIRE_THROWS_WITH(conv::Conv2d(rt, spec(2, 32, 4, 2, 4)),
                      Catch::Contains("'pad' = 4"));
  REQUIRE_THROWS_WITH(conv::Conv2d(rt, spec(4, 8, 3, 1, 1, 2)),
                      Catch::Contains("'in_cs' = 2"));
  conv::Conv2d cv(rt, spec(2, 16, 4, 2, 1));
  cl::Buffer p(rt, cv.n_params() * 4), x(rt, 64 * 4), y(rt, 64 * 4);
  REQUIRE_THROWS_WITH(cv.forward(p, 0, x, 1, 1, 8, y), Catch::Contains("too small"));
  REQUIRE_THROWS_WITH(cv.forward(p, 0, x, 1, 8, 8, y), Catch::Contains("'in'"));
  cl::Buffer big(rt, size_t(16) * 8 * 8 * 4);
  REQUIRE_THROWS_WITH(cv.forward(p, 0, big, 1, 8, 8, big, &big, 1.5f), Catch::Contains("'slope' = 1.5"));
}
