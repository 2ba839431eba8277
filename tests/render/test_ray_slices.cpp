// The ray-gradient reduction over compact rows and weight carving with a slice of work-items per
// ray (device profile ray_work_items > 1; kernels/render/ray_grad_slices.cl,
// weight_carve_slices.cl) against their double-precision host references (render_reference.hpp,
// surface_reference.hpp): rays of 0, 1, fewer than W and many rows, several slice widths and
// work-group sizes, the cpu profile's kernels (W = 1) held to the same bounds; carving's
// gradient also against finite differences; the same bits from run to run.
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

std::vector<float> to_float(const std::vector<double>& v) { return {v.begin(), v.end()}; }

// Σ_i |term_i| per output component: the scale of a float sum's rounding (floor of the check).
double max_abs_sum(int n_rays, int M, const std::vector<int>& offset, const std::vector<float>& t,
                   const std::vector<float>& gx) {
  double m = 0;
  for (int r = 0; r < n_rays; ++r)
    for (int c = 0; c < 3; ++c) {
      double a = 0;
      for (int i = 0; i < offset[size_t(r) + 1] - offset[size_t(r)]; ++i)
        a += std::abs(gx[3 * size_t(offset[size_t(r)] + i) + c]) *
             std::max(1.0f, t[size_t(r) * M + i]);
      m = std::max(m, a);
    }
  return m;
}

// Weight carving's terms and dL/dh0 (kernels/render/surface.cl's formulas) from the renderer's
// float weights `w`, as the kernels take them, with each sample's factor exp(-σδ) rounded to
// float as a kernel computes it and everything else in double: what remains between it and a
// kernel is the kernel's own association of its sums and products. (surface_reference.hpp's
// ref_carve_grad recomputes the weights in double; their float rounding, the same in every
// kernel, dominates the difference there.)
void ref_carve_from_weights(int n_rays, int M, float last, float near, float half_w, double scale,
                            const std::vector<float>& t, const std::vector<float>& h0,
                            const std::vector<float>& w, const std::vector<float>& target,
                            std::vector<double>& g_h0, std::vector<double>& terms) {
  g_h0.assign(t.size(), 0.0);
  terms.assign(size_t(n_rays), 0.0);
  for (int r = 0; r < n_rays; ++r) {
    if (!test::ref_has_return(target, r, near)) continue;
    const size_t b = size_t(r) * M;
    const float rr = target[3 * size_t(r)];
    std::vector<double> gw(M), after(M + 1, 0.0);  // after[i] = Σ_{k>=i} g_k w_k
    for (int i = 0; i < M; ++i) {
      const double m = std::abs(t[b + i] - rr) > half_w ? 1.0 : 0.0;
      terms[size_t(r)] += scale * m * double(w[b + i]) * w[b + i];
      gw[i] = 2 * scale * m * double(w[b + i]) * w[b + i];
    }
    for (int i = M - 1; i >= 0; --i) after[i] = after[i + 1] + gw[i];
    double trans = 1;
    for (int k = 0; k < M; ++k) {
      const float delta = k + 1 < M ? t[b + k + 1] - t[b + k] : last;
      trans *= double(std::exp(-std::exp(std::min(h0[b + k], 80.f)) * delta));  // T_{k+1}
      const double m = std::abs(t[b + k] - rr) > half_w ? 1.0 : 0.0;
      const double g = 2 * scale * m * w[b + k];
      g_h0[b + k] = delta * (g * trans - after[k + 1]) *
                    std::exp(std::clamp(double(h0[b + k]), -15.0, 15.0));
    }
  }
}

// The reduction over compact rows and over the full layout for each row count of `rows`.
void check_raygrad(std::initializer_list<int> rows, int n_rays,
                   const std::vector<std::pair<int, int>>& shapes) {
  auto& rt = test::runtime();
  for (const int M : rows) {
    const float bound = 1.0f;
    const auto t = test::make_uniform(size_t(n_rays) * M, 0.f, 2.f, 11 + M);
    const auto o = test::make_uniform(3 * size_t(n_rays), -0.8f, 0.8f, 12 + M);
    const auto d = test::make_uniform(3 * size_t(n_rays), -1.f, 1.f, 13 + M);
    // Live rows per ray: 0, 1, a few, M and everything between (early termination's counts).
    std::vector<int> offset(size_t(n_rays) + 1, 0);
    for (int r = 0; r < n_rays; ++r) offset[size_t(r) + 1] = offset[size_t(r)] + (r * 7) % (M + 1);
    const auto gx = test::make_uniform(3 * size_t(offset.back()) + 3, -1.f, 1.f, 14 + M);
    const auto gfull = test::make_uniform(3 * size_t(n_rays) * M, -1.f, 1.f, 15 + M);
    std::vector<int> full(size_t(n_rays) + 1);
    for (int r = 0; r <= n_rays; ++r) full[size_t(r)] = r * M;
    auto bt = cl::Buffer::from(rt, t), bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
    auto bgx = cl::Buffer::from(rt, gx), boff = cl::Buffer::from(rt, offset),
         bgf = cl::Buffer::from(rt, gfull);
    std::vector<double> ro, rd, fo, fd;
    test::ref_raygrad_rows<double>(n_rays, M, bound, offset, test::cast_vec<double>(t),
                                   test::cast_vec<double>(o), test::cast_vec<double>(d),
                                   test::cast_vec<double>(gx), ro, rd);
    test::ref_raygrad_rows<double>(n_rays, M, bound, full, test::cast_vec<double>(t),
                                   test::cast_vec<double>(o), test::cast_vec<double>(d),
                                   test::cast_vec<double>(gfull), fo, fd);
    // Floors at the largest Σ|term| of a sum: a float sum's rounding scales with it, not with
    // the sum (these cancel), so the check is normwise: |error| / Σ|term|.
    const double fl = max_abs_sum(n_rays, M, offset, t, gx),
                 fl_full = max_abs_sum(n_rays, M, full, t, gfull);
    for (const auto& [W, local] : shapes) {
      INFO("M = " << M << ", W = " << W << ", work-group " << local);
      test::ProfileScope scope(slice_profile(W, local));
      render::RayGradReducer red(rt);
      cl::Buffer go(rt, size_t(n_rays) * 12), gd(rt, size_t(n_rays) * 12);
      auto run = [&](const cl::Buffer* off, const cl::Buffer& g) {
        red.reduce_rows(off, bt, bo, bd, g, n_rays, M, bound, go, gd);
        return std::make_pair(go.read_vec<float>(3 * size_t(n_rays)),
                              gd.read_vec<float>(3 * size_t(n_rays)));
      };
      const auto rows = run(&boff, bgx);
      const auto whole = run(nullptr, bgf);
      // Measured on PoCL (all shapes, the cpu kernel alike): 9.6e-8 of Σ|term|.
      CHECK(test::sym_rel_err(rows.first, to_float(ro), fl) <= 5e-7);
      CHECK(test::sym_rel_err(rows.second, to_float(rd), fl) <= 5e-7);
      CHECK(test::sym_rel_err(whole.first, to_float(fo), fl_full) <= 5e-7);
      CHECK(test::sym_rel_err(whole.second, to_float(fd), fl_full) <= 5e-7);
      const auto again = run(&boff, bgx);
      CHECK(test::same_bits(again.first, rows.first));
      CHECK(test::same_bits(again.second, rows.second));
    }
  }
}

}  // namespace

TEST_CASE("Ray slices: the ray-gradient reduction over compact rows equals the double reference",
          "[render][raygrad][ray_slices]") {
  check_raygrad({1, 24, 100}, 41, kShapes);
}

namespace {
// Weight carving for each sample count of `samples`, from the same profile's forward weights;
// with `fd_check`, the W = 32 gradient against central differences too.
void check_carving(std::initializer_list<int> samples, int n_rays,
                   const std::vector<std::pair<int, int>>& shapes, bool fd_check) {
  auto& rt = test::runtime();
  render::RenderConfig cfg;
  cfg.weights.carve = 3.0f;
  const float near = cfg.near_m * kScale, far = cfg.far_m * kScale;
  const float half_w = 1.0f * kScale, last = cfg.bin_width(kScale);
  for (const int M : samples) {
    // Sorted jittered samples over [near, far], densities from clear to opaque; returns at a
    // random range, every fifth ray without one (label 0) and one return before near.
    const auto u = test::make_uniform(size_t(n_rays) * M, 0.f, 1.f, 20 + M);
    const auto h0 = test::make_uniform(size_t(n_rays) * M, -1.f, 3.f, 21 + M);
    const auto rr = test::make_uniform(size_t(n_rays), near, far, 22 + M);
    std::vector<float> t(u.size()), head(2 * u.size(), 0.f), target(3 * size_t(n_rays));
    for (size_t s = 0; s < t.size(); ++s) t[s] = near + ((s % M) + u[s]) * (far - near) / M;
    for (int r = 0; r < n_rays; ++r) {
      target[3 * size_t(r)] = r == 3 ? 0.5f * near : rr[size_t(r)];
      target[3 * size_t(r) + 1] = 0.5f;
      target[3 * size_t(r) + 2] = r % 5 == 4 ? 0.f : 1.f;
    }
    const std::vector<double> td(t.begin(), t.end()), hd(h0.begin(), h0.end());
    const double scale = cfg.weights.carve / n_rays;
    std::vector<double> terms_ref;
    test::ref_carve_loss<double>(n_rays, M, last, near, half_w, scale, td, hd, target, &terms_ref);
    const auto g_ref =
        test::ref_carve_grad<double>(n_rays, M, last, near, half_w, scale, td, hd, target);
    double max_ref = 0, max_term = 0;
    for (double v : g_ref) max_ref = std::max(max_ref, std::abs(v));
    for (double v : terms_ref) max_term = std::max(max_term, std::abs(v));
    REQUIRE(max_ref > 1e-4);
    auto bt = cl::Buffer::from(rt, t), bh = cl::Buffer::from(rt, h0),
         bhead = cl::Buffer::from(rt, head), btg = cl::Buffer::from(rt, target);
    for (const auto& [W, local] : shapes) {
      INFO("M = " << M << ", W = " << W << ", work-group " << local);
      test::ProfileScope scope(slice_profile(W, local));
      render::VolumeRenderer vr(rt, cfg, kScale);
      render::WeightCarving carving(rt, cfg, kScale, n_rays);
      cl::Buffer out(rt, size_t(n_rays) * 12), bw(rt, t.size() * 4);
      vr.forward(bt, bh, bhead, n_rays, M, out, bw);
      // The kernel ADDS to g_h0: from zeros (a base of 0.5 would round the gradients to its
      // ulp), then once more onto the result, which must double it exactly.
      auto run = [&]() {
        auto bgh = cl::Buffer::from(rt, std::vector<float>(t.size(), 0.0f));
        carving.add(bt, bh, bw, btg, n_rays, M, half_w, bgh);
        const auto g = bgh.read_vec<float>(t.size());
        const auto terms = carving.terms().read_vec<float>(size_t(n_rays));
        carving.add(bt, bh, bw, btg, n_rays, M, half_w, bgh);
        auto twice = bgh.read_vec<float>(t.size());
        for (auto& v : twice) v *= 0.5f;
        CHECK(test::same_bits(twice, g));
        return std::make_pair(g, terms);
      };
      const auto dev = run();
      std::vector<double> g_w, terms_w;
      ref_carve_from_weights(n_rays, M, last, near, half_w, scale, t, h0,
                             bw.read_vec<float>(t.size()), target, g_w, terms_w);
      // Measured on PoCL: terms 3.3e-7; the gradient with floors of 1e-6 and 1e-4 of the
      // largest 3.9e-4 and 6.3e-5 (slices), 0.021 and 1.4e-3 (W = 1: surface.cl forms the suffix
      // sum as total − prefix, which cancels), nmse 2.6e-13; against the all-double reference
      // nmse 3.0e-13 (terms 3.9e-14).
      CHECK(test::sym_rel_err(dev.second, to_float(terms_w), 1e-6 * max_term) <= 1e-6);
      CHECK(test::nmse(dev.second, to_float(terms_ref)) <= 1e-13);
      if (W > 1) {
        CHECK(test::sym_rel_err(dev.first, to_float(g_w), 1e-6 * max_ref) <= 1e-3);
        CHECK(test::sym_rel_err(dev.first, to_float(g_w), 1e-4 * max_ref) <= 2e-4);
      } else {
        CHECK(test::sym_rel_err(dev.first, to_float(g_w), 1e-4 * max_ref) <= 3e-3);
      }
      CHECK(test::nmse(dev.first, to_float(g_w)) <= 1e-12);
      CHECK(test::nmse(dev.first, to_float(g_ref)) <= 1e-12);
      for (int r = 4; r < n_rays; r += 5)  // no return: no term, no gradient
        for (int i = 0; i < M; ++i) CHECK(dev.first[size_t(r) * M + i] == 0.0f);
      const auto again = run();
      CHECK(test::same_bits(again.first, dev.first));
      CHECK(test::same_bits(again.second, dev.second));
      if (!fd_check || W != 32) continue;
      // Central differences of the double loss on a spread of samples.
      for (size_t i = 1; i < hd.size(); i += 7) {
        auto hp = hd, hm = hd;
        const double eps = 1e-5;
        hp[i] += eps, hm[i] -= eps;
        const double fd =
            (test::ref_carve_loss<double>(n_rays, M, last, near, half_w, scale, td, hp, target) -
             test::ref_carve_loss<double>(n_rays, M, last, near, half_w, scale, td, hm, target)) /
            (2 * eps);
        INFO("sample " << i);
        CHECK(std::abs(fd - dev.first[i]) <= 1e-4 * max_ref + 1e-3 * std::abs(fd));
      }
    }
  }
}
}  // namespace

TEST_CASE("Ray slices: weight carving equals the double reference and finite differences",
          "[render][surface][ray_slices]") {
  check_carving({1, 5, 25, 67}, 29, kShapes, true);
}

// The Oclgrind case (tests/oclgrind/CMakeLists.txt, render_slices): the gpu profile's slice of
// 32 in groups of 64 and 16 in groups of 48, a few rays.
TEST_CASE("Ray slices on a small case", "[render][ray_slices][small]") {
  const std::vector<std::pair<int, int>> shapes = {{32, 64}, {16, 48}};
  check_raygrad({5, 37}, 7, shapes);
  check_carving({5, 37}, 7, shapes, false);
}
