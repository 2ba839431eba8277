// Volume rendering with a slice of work-items per ray (device profile ray_work_items > 1;
// kernels/render/volume_slices.cl): forward, weights and backward against double-precision host
// references at sample counts that are not a multiple of the slice (S < W, S = 1), on opaque,
// empty and underflowing rays, for several slice widths and work-group sizes, with the cpu
// profile's kernels (volume.cl, W = 1) held to the same bounds; the backward also against
// finite differences; the same bits from run to run.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "render/ray_gradient.hpp"
#include "render/volume_renderer.hpp"
#include "render/weight_carving.hpp"
#include "render_reference.hpp"
#include "render_test_data.hpp"
#include "slice_profiles.hpp"
#include "support/test_device.hpp"
#include "surface_reference.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
const float kScale = 0.0125f;  // 1 / 80 m

using test::slice_profile;
const auto& kShapes = test::kSliceShapes;

// Rays of five kinds (ray r: kind r % 5): random densities; opaque from the first sample; empty
// (h0 = -15, σ ≈ 3e-7); a wall half way; dense enough that T underflows float.
struct Rays {
  int n = 0, S = 0;
  std::vector<float> t, h0, head;
};
Rays make_kinds(int n, int S, uint64_t seed) {
  Rays in{n, S, {}, {}, {}};
  const render::RenderConfig cfg;
  const float near = cfg.near_m * kScale, far = cfg.far_m * kScale;
  const auto u = test::make_uniform(size_t(n) * S, 0.f, 1.f, seed);
  const auto h = test::make_uniform(size_t(n) * S, -2.f, 4.f, seed + 1);
  in.head = test::make_uniform(2 * size_t(n) * S, -4.f, 4.f, seed + 2);
  in.t.resize(u.size());
  in.h0.resize(u.size());
  for (int r = 0; r < n; ++r)
    for (int i = 0; i < S; ++i) {
      const size_t s = size_t(r) * S + i;
      in.t[s] = near + (i + u[s]) * (far - near) / S;
      switch (r % 5) {
        case 0: in.h0[s] = h[s]; break;
        case 1: in.h0[s] = 12.f; break;
        case 2: in.h0[s] = -15.f; break;
        case 3: in.h0[s] = 2 * i < S ? -12.f : 12.f; break;
        default: in.h0[s] = 6.f + h[s]; break;  // σ δ ≈ 5 ... 270 a sample
      }
    }
  return in;
}

struct Fwd {
  std::vector<float> out, w, w_only;
};
Fwd run_fwd(const cl::DeviceProfile& p, const Rays& in) {
  auto& rt = test::runtime();
  test::ProfileScope scope(p);
  render::RenderConfig cfg;
  render::VolumeRenderer vr(rt, cfg, kScale);
  auto bt = cl::Buffer::from(rt, in.t), bh = cl::Buffer::from(rt, in.h0),
       bhead = cl::Buffer::from(rt, in.head);
  cl::Buffer out(rt, size_t(in.n) * 12), w(rt, in.t.size() * 4), w2(rt, in.t.size() * 4);
  vr.forward(bt, bh, bhead, in.n, in.S, out, w);
  vr.weights(bt, bh, in.n, in.S, w2);
  return {out.read_vec<float>(size_t(in.n) * 3), w.read_vec<float>(in.t.size()),
          w2.read_vec<float>(in.t.size())};
}

struct Bwd {
  std::vector<float> h0, head;
};
Bwd run_bwd(const cl::DeviceProfile& p, const Rays& in, const std::vector<float>& w,
            const std::vector<float>& g) {
  auto& rt = test::runtime();
  test::ProfileScope scope(p);
  render::RenderConfig cfg;
  render::VolumeRenderer vr(rt, cfg, kScale);
  auto bt = cl::Buffer::from(rt, in.t), bh = cl::Buffer::from(rt, in.h0),
       bhead = cl::Buffer::from(rt, in.head), bw = cl::Buffer::from(rt, w),
       bg = cl::Buffer::from(rt, g);
  cl::Buffer gh0(rt, in.t.size() * 4), ghead(rt, in.t.size() * 8);
  vr.backward(bt, bh, bhead, bw, bg, in.n, in.S, gh0, ghead);
  return {gh0.read_vec<float>(in.t.size()), ghead.read_vec<float>(2 * in.t.size())};
}

// The backward of ref_fwd_float_factors (render_reference.hpp's ref_volume_bwd's formulas: dL/dτ_i
// = T_{i+1} c_i − Σ_{k>i} w_k c_k, c = g · (t, sigmoid(a), sigmoid(b))), in double after the float
// factors.
void ref_bwd_float_factors(const Rays& in, double last, const std::vector<float>& g,
                           std::vector<double>& g_h0, std::vector<double>& g_head) {
  g_h0.assign(in.t.size(), 0.0);
  g_head.assign(2 * in.t.size(), 0.0);
  for (int r = 0; r < in.n; ++r) {
    const size_t b = size_t(r) * in.S;
    std::vector<double> e(in.S), w(in.S), c(in.S), after(in.S + 1, 0.0);  // after: Σ_{k>=i} w c
    double trans = 1;
    for (int i = 0; i < in.S; ++i) {
      const size_t s = b + i;
      const float delta = i + 1 < in.S ? in.t[s + 1] - in.t[s] : float(last);
      e[i] = std::exp(-std::exp(std::min(in.h0[s], 80.f)) * delta);
      w[i] = trans * (1.0 - e[i]);
      trans *= e[i];
      c[i] = g[3 * r] * double(in.t[s]) +
             g[3 * r + 1] * test::ref_sigmoid(double(in.head[2 * s])) +
             g[3 * r + 2] * test::ref_sigmoid(double(in.head[2 * s + 1]));
    }
    for (int i = in.S - 1; i >= 0; --i) after[i] = after[i + 1] + w[i] * c[i];
    trans = 1;
    for (int i = 0; i < in.S; ++i) {
      const size_t s = b + i;
      const float delta = i + 1 < in.S ? in.t[s + 1] - in.t[s] : float(last);
      trans *= e[i];
      g_h0[s] = (trans * c[i] - after[i + 1]) * delta *
                std::exp(std::clamp(double(in.h0[s]), -15.0, 15.0));
      const double sp = test::ref_sigmoid(double(in.head[2 * s])),
                   si = test::ref_sigmoid(double(in.head[2 * s + 1]));
      g_head[2 * s] = g[3 * r + 1] * w[i] * sp * (1 - sp);
      g_head[2 * s + 1] = g[3 * r + 2] * w[i] * si * (1 - si);
    }
  }
}

std::vector<float> to_float(const std::vector<double>& v) { return {v.begin(), v.end()}; }

// ref_volume_fwd with each sample's factor exp(-σδ) (and δ) rounded to float as a float kernel
// computes it, the transmittance and the sums in double: what remains between it and a kernel
// is the kernel's own association of the products and sums (and exp's last bits), not the
// float formula's 1 - exp(-σδ) of thin samples, whose rounding (relative 1e-7 / σδ) both
// kernels share.
void ref_fwd_float_factors(const Rays& in, double last, std::vector<double>& out,
                           std::vector<double>& w) {
  out.assign(size_t(in.n) * 3, 0.0);
  w.assign(in.t.size(), 0.0);
  for (int r = 0; r < in.n; ++r) {
    double trans = 1;
    for (int i = 0; i < in.S; ++i) {
      const size_t s = size_t(r) * in.S + i;
      const float delta = i + 1 < in.S ? in.t[s + 1] - in.t[s] : float(last);
      const double e = std::exp(-std::exp(std::min(in.h0[s], 80.f)) * delta);
      w[s] = trans * (1.0 - e);
      out[3 * size_t(r)] += w[s] * in.t[s];
      out[3 * size_t(r) + 1] += w[s] * test::ref_sigmoid(double(in.head[2 * s]));
      out[3 * size_t(r) + 2] += w[s] * test::ref_sigmoid(double(in.head[2 * s + 1]));
      trans *= e;
    }
  }
}

double last_delta() { return render::RenderConfig{}.bin_width(kScale); }

}  // namespace

namespace {
// The forward and the weights at each sample count of `samples`, n_rays rays of make_kinds.
void check_forward(std::initializer_list<int> samples, int n_rays,
                   const std::vector<std::pair<int, int>>& shapes) {
  for (const int S : samples) {
    const Rays in = make_kinds(n_rays, S, 100 + S);
    std::vector<double> out_ff, w_ff, out_ref, w_ref;
    ref_fwd_float_factors(in, last_delta(), out_ff, w_ff);
    test::ref_volume_fwd<double>(in.n, S, last_delta(), test::cast_vec<double>(in.t),
                                 test::cast_vec<double>(in.h0), test::cast_vec<double>(in.head),
                                 out_ref, w_ref);
    for (const auto& [W, local] : shapes) {
      INFO("S = " << S << ", W = " << W << ", work-group " << local);
      const Fwd dev = run_fwd(slice_profile(W, local), in);
      // Measured on PoCL (all shapes, the cpu kernels alike): sums 3.6e-7, weights 1.9e-5 (thin
      // samples: exp's last bit in 1 − e), nmse 1.2e-15; against the all-double reference nmse
      // 4.5e-14 (sums) and 8.5e-15 (weights).
      CHECK(test::sym_rel_err(dev.out, to_float(out_ff), 1e-6) <= 1e-6);
      CHECK(test::sym_rel_err(dev.w, to_float(w_ff), 1e-7) <= 5e-5);
      CHECK(test::nmse(dev.w, to_float(w_ff)) <= 5e-15);
      CHECK(test::nmse(dev.out, to_float(out_ref)) <= 1e-13);
      CHECK(test::nmse(dev.w, to_float(w_ref)) <= 3e-14);
      CHECK(test::same_bits(dev.w_only, dev.w));  // the weights kernel shares the forward's code
      const Fwd again = run_fwd(slice_profile(W, local), in);
      CHECK(test::same_bits(again.out, dev.out));
      CHECK(test::same_bits(again.w, dev.w));
    }
  }
}
}  // namespace

TEST_CASE("Volume slices: forward and weights equal the double reference at any sample count",
          "[render][volume][volume_slices]") {
  check_forward({1, 5, 31, 32, 67, 100}, 23, kShapes);
}

TEST_CASE("Volume slices: opaque rays put their weight on the first sample, empty rays none",
          "[render][volume][volume_slices]") {
  const int S = 45;
  const Rays in = make_kinds(10, S, 7);
  const Fwd dev = run_fwd(slice_profile(32), in);
  for (int r = 1; r < in.n; r += 5) {  // opaque: w_0 = 1 - exp(-σδ) = 1, T = 0 after it
    CHECK(dev.w[size_t(r) * S] == 1.0f);
    for (int i = 1; i < S; ++i) CHECK(dev.w[size_t(r) * S + i] == 0.0f);
    CHECK(dev.out[3 * size_t(r)] == in.t[size_t(r) * S]);
  }
  for (int r = 2; r < in.n; r += 5) {  // empty: σδ ≈ 3e-9 a sample
    double sum = 0;
    for (int i = 0; i < S; ++i) sum += dev.w[size_t(r) * S + i];
    CHECK(sum < 1e-6);
  }
}

namespace {
// The backward at each sample count of `samples` from the same profile's forward weights.
void check_backward(std::initializer_list<int> samples, int n_rays,
                    const std::vector<std::pair<int, int>>& shapes) {
  for (const int S : samples) {
    const Rays in = make_kinds(n_rays, S, 200 + S);
    const auto g = test::make_uniform(3 * size_t(in.n), -1.f, 1.f, 300 + S);
    std::vector<double> h0_ref, head_ref;
    ref_bwd_float_factors(in, last_delta(), g, h0_ref, head_ref);
    // Floors at 1e-6 of the largest gradient: dL/dτ = T c − Σ w c cancels, so an entry carries
    // the rounding of the sums it is a difference of, not its own.
    auto floor_of = [](const std::vector<double>& v) {
      double m = 0;
      for (double x : v) m = std::max(m, std::abs(x));
      return 1e-6 * m;
    };
    const double fl_h0 = floor_of(h0_ref), fl_head = floor_of(head_ref);
    for (const auto& [W, local] : shapes) {
      INFO("S = " << S << ", W = " << W << ", work-group " << local);
      const Fwd fwd = run_fwd(slice_profile(W, local), in);
      const Bwd dev = run_bwd(slice_profile(W, local), in, fwd.w, g);
      // Measured on PoCL: dL/dh0 1.1e-4 (the cpu kernel 5.9e-5), 1.2e-5 with a floor of 1e-3,
      // nmse 6.2e-14; dL/dhead 1.9e-5 (the cpu kernel's; slices 7.4e-6), nmse 2.3e-14.
      CHECK(test::sym_rel_err(dev.h0, to_float(h0_ref), fl_h0) <= 3e-4);
      CHECK(test::sym_rel_err(dev.h0, to_float(h0_ref), 1e3 * fl_h0) <= 3e-5);
      CHECK(test::nmse(dev.h0, to_float(h0_ref)) <= 2e-13);
      CHECK(test::sym_rel_err(dev.head, to_float(head_ref), fl_head) <= 5e-5);
      CHECK(test::nmse(dev.head, to_float(head_ref)) <= 1e-13);
      const Bwd again = run_bwd(slice_profile(W, local), in, fwd.w, g);
      CHECK(test::same_bits(again.h0, dev.h0));
      CHECK(test::same_bits(again.head, dev.head));
    }
  }
}
}  // namespace

TEST_CASE("Volume slices: backward equals the double reference and finite differences",
          "[render][volume][volume_slices]") {
  check_backward({1, 5, 21, 31, 67, 100}, 23, kShapes);
  // Central differences of L = g · out(h0, head) in double on the random-density rays.
  const int n = 4, S = 21;
  Rays in = make_kinds(n, S, 400);
  for (int r = 0; r < n; ++r)  // every ray translucent: all its samples carry gradient
    for (int i = 0; i < S; ++i) in.h0[size_t(r) * S + i] = 0.5f + 0.1f * float((r * S + i) % 7);
  const auto g = test::make_uniform(3 * size_t(n), -1.f, 1.f, 401);
  std::vector<float> fd_h0, fd_head;
  test::fd_volume_grads(n, S, last_delta(), in.t, in.h0, in.head, g, fd_h0, fd_head);
  for (const int W : {8, 32}) {
    INFO("W = " << W);
    const Fwd fwd = run_fwd(slice_profile(W), in);
    const Bwd dev = run_bwd(slice_profile(W), in, fwd.w, g);
    CHECK(test::sym_rel_err(dev.h0, fd_h0, 1e-6) <= 1e-4);
    CHECK(test::sym_rel_err(dev.head, fd_head, 1e-6) <= 1e-4);
  }
}

// The Oclgrind case (tests/oclgrind/CMakeLists.txt, render_slices): the gpu profile's slice of
// 32 in groups of 64 and 16 in groups of 48, S below, at and above a slice, a few rays.
TEST_CASE("Volume slices on a small case", "[render][volume_slices][small]") {
  const std::vector<std::pair<int, int>> shapes = {{32, 64}, {16, 48}};
  check_forward({1, 5, 37}, 7, shapes);
  check_backward({1, 5, 37}, 7, shapes);
}
