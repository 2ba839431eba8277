// Conv2d's local_tiles kernels (device profile gemm = "local_tiles", the "gpu" profile's;
// kernels/conv/conv2d_tiles.cl) on the test device: the host reference with the profile's
// register block and with the 1 x 1 block of small launches (bit-identical to each other: every
// sum keeps its order), within float rounding of the cpu_tiles kernels (conv2d.cl and
// conv2d_narrow.cl) on the PatchGAN's and the ray-drop U-Net's strided and padded shapes.
// The other conv cases run under the gpu profile too: ctest conv_gpu_profile
// (tests/conv/CMakeLists.txt).
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "conv/conv2d.hpp"
#include "reference.hpp"
#include "support/device_tolerance.hpp"
#include "support/gemm_profiles.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using sgnlf::test::same_bits;
using sgnlf::test::tiles_profile;
using sgnlf::test::cpu_tiles_profile;

namespace {
using test::uniform;

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
void zero_padding(std::vector<float>& v, int c, int cs) {
  for (size_t i = 0; i < v.size(); ++i)
    if (int(i % size_t(cs)) >= c) v[i] = 0.0f;
}
// The gpu profile; `block` 0: the 1 x 1 block everywhere, 1: the profile's block everywhere.
// The d_in channels < c_in of an NHWC buffer with stride cs.
std::vector<float> channels(const std::vector<float>& v, int c, int cs) {
  std::vector<float> r;
  for (size_t i = 0; i < v.size(); ++i)
    if (int(i % size_t(cs)) < c) r.push_back(v[i]);
  return r;
}

struct Case {
  const char* name;
  conv::Conv2dSpec spec;
  int n, h, w;
};
// The PatchGAN's layers (4 x 4, stride 2 then 1, pad 1, [D_ij, D_j] input of stride 2) and the
// ray-drop U-Net's (3 x 3 and 1 x 1, stride 1, pad k / 2, in_cs = c_in), odd sizes.
const std::vector<Case>& cases() {
  static const std::vector<Case> c = {
      {"patchgan 2->32 k4 s2", spec(2, 32, 4, 2, 1, 2), 2, 17, 45},
      {"patchgan 32->64 k4 s2", spec(32, 64, 4, 2, 1), 2, 9, 23},
      {"patchgan 64->128 k4 s1", spec(64, 128, 4, 1, 1), 1, 6, 13},
      {"patchgan 128->1 k4 s1", spec(128, 1, 4, 1, 1), 2, 5, 12},
      {"unet 3->16 k3", spec(3, 16, 3, 1, 1, 3), 2, 9, 31},
      {"unet 48->32 k3", spec(48, 32, 3, 1, 1, 48), 1, 8, 21},
      {"unet 16->1 k1", spec(16, 1, 1, 1, 0, 16), 2, 6, 17},
      {"odd 5->20 k3 s2 in_cs 8", spec(5, 20, 3, 2, 1, 8), 3, 8, 11},
      {"odd 3->7 k4 s2 pad 0", spec(3, 7, 4, 2, 0), 1, 10, 21},
      {"stride 3 20->17 k4 p2", spec(20, 17, 4, 3, 2), 2, 11, 14},
  };
  return c;
}

struct Data {
  size_t off = 16;
  std::vector<float> params, slice, in, d_out;
};
Data make_data(const Case& c, uint64_t seed) {
  const auto& s = c.spec;
  Data d;
  conv::Conv2d probe(test::runtime(), s);
  d.params.assign(d.off + probe.n_params(), 0.0f);
  probe.init_params(d.params, d.off, seed, 0.2f);
  for (int o = 0; o < s.c_out; ++o) d.params[d.off + s.bias_index(o)] = 0.05f * float(o % 5 - 2);
  d.slice.assign(d.params.begin() + long(d.off), d.params.end());
  const int ho = s.out_size(c.h), wo = s.out_size(c.w);
  d.in = uniform(size_t(c.n) * c.h * c.w * s.input_cs(), -1.0f, 1.0f, seed + 1);
  d.d_out = uniform(size_t(c.n) * ho * wo * s.out_cs(), -1.0f, 1.0f, seed + 2);
  zero_padding(d.d_out, s.c_out, s.out_cs());
  return d;
}

// One forward (plain and with the fused activation) and one backward.
struct Pass {
  bool tiles = false;
  std::vector<float> out, act, grad, d_in;
};
Pass run(const cl::DeviceProfile& profile, const Case& c, const Data& d) {
  auto& rt = test::runtime();
  test::ProfileScope scoped(profile);
  conv::Conv2d cv(rt, c.spec);
  Pass r;
  r.tiles = cv.local_tiles();
  auto b_p = cl::Buffer::from(rt, d.params), b_in = cl::Buffer::from(rt, d.in);
  auto b_dout = cl::Buffer::from(rt, d.d_out);
  auto b_out = cl::Buffer::from(rt, std::vector<float>(d.d_out.size(), 5.0f));
  auto b_act = cl::Buffer::from(rt, std::vector<float>(d.d_out.size(), 5.0f));
  auto b_din = cl::Buffer::from(rt, std::vector<float>(d.in.size(), 7.0f));
  auto b_grad = cl::Buffer::from(rt, std::vector<float>(d.params.size(), 9.0f));
  cv.forward(b_p, d.off, b_in, c.n, c.h, c.w, b_out);
  r.out = b_out.read_all<float>();
  cv.forward(b_p, d.off, b_in, c.n, c.h, c.w, b_out, &b_act, 0.2f);
  r.act = b_act.read_all<float>();
  REQUIRE(same_bits(b_out.read_all<float>(), r.out));
  cv.backward(b_p, d.off, b_in, c.n, c.h, c.w, b_dout, &b_grad, d.off, &b_din);
  r.grad = b_grad.read_all<float>();
  r.d_in = b_din.read_all<float>();
  return r;
}
}  // namespace

TEST_CASE("Conv2d local_tiles forward matches the host reference and cpu_tiles",
          "[conv][conv2d][conv_tiles]") {
  for (const auto& c : cases()) {
    SECTION(c.name) {
      const auto& s = c.spec;
      const Data d = make_data(c, 3);
      const Pass p1 = run(tiles_profile(0), c, d), p4 = run(tiles_profile(1), c, d);
      const Pass cpu = run(cpu_tiles_profile(), c, d);
      REQUIRE(p1.tiles);
      REQUIRE(p4.tiles);
      REQUIRE_FALSE(cpu.tiles);
      const auto ref = test::ref::conv2d_fwd(s, d.slice, d.in, c.n, c.h, c.w);
      // Sums of up to 2048 products of O(0.2): float rounding against the double reference,
      // absolute (~1e-5) below outputs of 0.1 where the sums cancel.
      CHECK(test::sym_rel_err(p4.out, ref, 1e-1) <= 1e-4);
      CHECK(test::nmse(p4.out, ref) <= 1e-11);
      CHECK(test::sym_rel_err(p4.out, cpu.out, 1e-2) <= 1e-4);
      // Padding channels 0, the activation a selection or one product of that output.
      for (size_t i = 0; i < p4.out.size(); ++i)
        if (int(i % size_t(s.out_cs())) >= s.c_out) REQUIRE(p4.out[i] == 0.0f);
      CHECK(p4.act == test::ref::leaky_relu_fwd(p4.out, 0.2f));
      // The 1 x 1 and the profile's block: the same fma's in the same order.
      CHECK(same_bits(p1.out, p4.out));
      CHECK(same_bits(p1.act, p4.act));
    }
  }
}

TEST_CASE("Conv2d local_tiles input backward matches the host reference and cpu_tiles",
          "[conv][conv2d][conv_tiles]") {
  for (const auto& c : cases()) {
    SECTION(c.name) {
      const auto& s = c.spec;
      const int ics = s.input_cs();
      const Data d = make_data(c, 7);
      const Pass p1 = run(tiles_profile(0), c, d), p4 = run(tiles_profile(1), c, d);
      const Pass cpu = run(cpu_tiles_profile(), c, d);
      std::vector<float> din_ref;
      test::ref::conv2d_bwd(s, d.slice, d.in, c.n, c.h, c.w, d.d_out, din_ref);
      const auto dev = channels(p4.d_in, s.c_in, ics), ref = channels(din_ref, s.c_in, ics);
      CHECK(test::sym_rel_err(dev, ref, 1e-1) <= 1e-4);
      CHECK(test::nmse(dev, ref) <= 1e-11);
      CHECK(test::sym_rel_err(dev, channels(cpu.d_in, s.c_in, ics), 1e-1) <= 1e-4);
      // Only the c_in channels are written.
      for (size_t i = 0; i < p4.d_in.size(); ++i)
        if (int(i % size_t(ics)) >= s.c_in) REQUIRE(p4.d_in[i] == 7.0f);
      CHECK(same_bits(p1.d_in, p4.d_in));
    }
  }
}

// L = Σ r · out is linear in the parameters and the input: central differences of the device
// forward are exact up to its float rounding.
TEST_CASE("Conv2d local_tiles gradients agree with finite differences of the forward",
          "[conv][conv2d][conv_tiles][fd]") {
  auto& rt = test::runtime();
  test::ProfileScope scoped(tiles_profile(1));
  for (const auto& s : {spec(3, 5, 3, 2, 1), spec(2, 17, 4, 2, 1, 2), spec(20, 2, 4, 1, 1),
                        spec(16, 18, 3, 1, 1, 16), spec(4, 6, 4, 3, 2)}) {
    conv::Conv2d cv(rt, s);
    REQUIRE(cv.local_tiles());
    const int n = 2, h = 7, w = 9, ho = s.out_size(h), wo = s.out_size(w);
    std::vector<float> params(cv.n_params(), 0.0f);
    cv.init_params(params, 0, 11, 0.3f);
    for (int o = 0; o < s.c_out; ++o) params[s.bias_index(o)] = 0.1f;
    const auto in = uniform(size_t(n) * h * w * s.input_cs(), -1.0f, 1.0f, 12);
    auto r = uniform(size_t(n) * ho * wo * s.out_cs(), -1.0f, 1.0f, 13);
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
    const float step = 1e-2f;
    std::vector<float> fd, an;
    for (size_t k = 0; k < in.size(); k += 3) {
      if (int(k % size_t(s.input_cs())) >= s.c_in) continue;
      auto xp = in, xm = in;
      xp[k] += step;
      xm[k] -= step;
      fd.push_back(float((loss(params, xp) - loss(params, xm)) / (2.0 * step)));
      an.push_back(din[k]);
    }
    REQUIRE(fd.size() > 20);
    CHECK(test::sym_rel_err(fd, an, 1e-1) <= 4e-3);
  }
}

TEST_CASE("Conv2d local_tiles weight gradient matches the host reference and cpu_tiles",
          "[conv][conv2d][conv_tiles]") {
  for (const auto& c : cases()) {
    SECTION(c.name) {
      const auto& s = c.spec;
      const Data d = make_data(c, 9);
      const Pass p1 = run(tiles_profile(0), c, d), p4 = run(tiles_profile(1), c, d);
      const Pass again = run(tiles_profile(1), c, d);
      const Pass cpu = run(cpu_tiles_profile(), c, d);
      std::vector<float> din_ref;
      const auto ref = test::ref::conv2d_bwd(s, d.slice, d.in, c.n, c.h, c.w, d.d_out, din_ref);
      const std::vector<float> g(p4.grad.begin() + long(d.off), p4.grad.end());
      const std::vector<float> g_cpu(cpu.grad.begin() + long(d.off), cpu.grad.end());
      // Sums over up to ~1500 pixels of O(1) products: absolute rounding below 1.
      CHECK(test::sym_rel_err(g, ref, 1.0) <= 1e-4);
      CHECK(test::nmse(g, ref) <= 1e-11);
      CHECK(test::sym_rel_err(g, g_cpu, 1.0) <= 1e-4);
      CHECK(p4.grad[d.off - 1] == 9.0f);  // outside the slice: untouched
      for (int o = s.c_out; o < s.out_cs(); ++o) CHECK(g[s.bias_index(o)] == 0.0f);
      // Deterministic for the shape: a repeat and the 1 x 1 block give the same bits.
      CHECK(same_bits(p4.grad, again.grad));
      CHECK(same_bits(p1.grad, p4.grad));
    }
  }
}

TEST_CASE("Conv2d local_tiles weight gradient agrees with finite differences",
          "[conv][conv2d][conv_tiles][fd]") {
  auto& rt = test::runtime();
  test::ProfileScope scoped(tiles_profile(1));
  for (const auto& s : {spec(3, 5, 3, 2, 1), spec(2, 17, 4, 2, 1, 2), spec(20, 2, 4, 1, 1),
                        spec(4, 6, 4, 3, 2)}) {
    conv::Conv2d cv(rt, s);
    const int n = 2, h = 7, w = 9, ho = s.out_size(h), wo = s.out_size(w);
    std::vector<float> params(cv.n_params(), 0.0f);
    cv.init_params(params, 0, 21, 0.3f);
    for (int o = 0; o < s.c_out; ++o) params[s.bias_index(o)] = 0.1f;
    const auto in = uniform(size_t(n) * h * w * s.input_cs(), -1.0f, 1.0f, 22);
    auto r = uniform(size_t(n) * ho * wo * s.out_cs(), -1.0f, 1.0f, 23);
    zero_padding(r, s.c_out, s.out_cs());
    auto b_p = cl::Buffer::from(rt, params), b_in = cl::Buffer::from(rt, in);
    auto b_r = cl::Buffer::from(rt, r);
    cl::Buffer b_out(rt, r.size() * 4), b_g(rt, params.size() * 4);
    cv.backward(b_p, 0, b_in, n, h, w, b_r, &b_g, 0, nullptr);
    const auto grad = b_g.read_all<float>();
    auto loss = [&](const std::vector<float>& p) {
      b_p.write_vec(p);
      cv.forward(b_p, 0, b_in, n, h, w, b_out);
      const auto out = b_out.read_all<float>();
      double l = 0;
      for (size_t i = 0; i < out.size(); ++i) l += double(out[i]) * r[i];
      return l;
    };
    const float step = 1e-2f;
    std::vector<float> fd, an;
    for (size_t k = 0; k < params.size(); k += 5) {
      if (grad[k] == 0.0f) continue;  // padding columns
      auto pp = params, pm = params;
      pp[k] += step;
      pm[k] -= step;
      fd.push_back(float((loss(pp) - loss(pm)) / (2.0 * step)));
      an.push_back(grad[k]);
    }
    REQUIRE(fd.size() > 20);
    CHECK(test::sym_rel_err(fd, an, 1e-1) <= 4e-3);
  }
}

// Small shapes for Oclgrind (tests/oclgrind, oclgrind_conv): every local_tiles kernel with both
// register blocks, strided, padded, narrow and wide, against the host reference and cpu_tiles.
TEST_CASE("Conv2d local_tiles on small shapes match the reference and cpu_tiles",
          "[conv][conv2d][conv_tiles][small]") {
  const std::vector<Case> small = {
      {"patchgan 2->32 k4 s2", spec(2, 32, 4, 2, 1, 2), 1, 6, 9},
      {"17->2 k4 s1 p1", spec(17, 2, 4, 1, 1), 1, 5, 6},
      {"unet 3->20 k3", spec(3, 20, 3, 1, 1, 3), 2, 4, 5},
      {"stride 3 5->7 k4 p2", spec(5, 7, 4, 3, 2), 1, 7, 8},
  };
  for (const auto& c : small) {
    SECTION(c.name) {
      const auto& s = c.spec;
      const int ics = s.input_cs();
      const Data d = make_data(c, 31);
      const Pass p1 = run(tiles_profile(0), c, d), p4 = run(tiles_profile(1), c, d);
      const Pass cpu = run(cpu_tiles_profile(), c, d);
      std::vector<float> din_ref;
      const auto out_ref = test::ref::conv2d_fwd(s, d.slice, d.in, c.n, c.h, c.w);
      const auto g_ref = test::ref::conv2d_bwd(s, d.slice, d.in, c.n, c.h, c.w, d.d_out, din_ref);
      const std::vector<float> g(p4.grad.begin() + long(d.off), p4.grad.end());
      CHECK(test::sym_rel_err(p4.out, out_ref, 1e-1) <= 1e-4);
      CHECK(test::sym_rel_err(g, g_ref, 1.0) <= 1e-4);
      CHECK(test::sym_rel_err(channels(p4.d_in, s.c_in, ics), channels(din_ref, s.c_in, ics),
                              1e-1) <= 1e-4);
      CHECK(test::sym_rel_err(p4.out, cpu.out, 1e-1) <= 1e-4);
      CHECK(test::sym_rel_err(p4.grad, cpu.grad, 1.0) <= 1e-4);
      // The c_in channels (cpu_tiles' conv2d_bwd_in also zeroes c_in .. 16-aligned ones).
      CHECK(test::sym_rel_err(channels(p4.d_in, s.c_in, ics), channels(cpu.d_in, s.c_in, ics),
                              1e-1) <= 1e-4);
      CHECK(same_bits(p1.out, p4.out));
      CHECK(same_bits(p1.grad, p4.grad));
      CHECK(same_bits(p1.d_in, p4.d_in));
    }
  }
}
