// The gpu profile's sampling kernels (ray_work_items > 1): render_sample_importance_wide (one
// work-item per output sample over a cooperative CDF in local memory) and
// render_sample_surface_wide (one work-item per sample), against the host references and the
// cpu profile's per-ray kernels, and run to run.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <utility>
#include <vector>

#include "cl/device_profile.hpp"
#include "render/ray_sampler.hpp"
#include "render/surface_sampler.hpp"
#include "render_reference.hpp"
#include "render_test_data.hpp"
#include "support/test_device.hpp"
#include "surface_reference.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
const float kScale = 0.0125f;  // 1 / 80 m

struct Merged {
  std::vector<float> t, x;
  std::vector<int> src;
};

cl::DeviceProfile lanes_profile(int lanes) {
  cl::DeviceProfile p = cl::gpu_profile();
  p.ray_work_items = lanes;
  return p;
}

// The importance samples of `cfg` under profile `p` (the sampler made under it).
Merged importance(const cl::DeviceProfile& p, const render::RenderConfig& cfg, int n_rays,
                  const std::vector<float>& o, const std::vector<float>& d,
                  const std::vector<float>& tc, const std::vector<float>& wc, bool jitter) {
  auto& rt = test::runtime();
  test::ProfileScope scope(p);
  render::RaySampler sampler(rt, cfg, kScale);
  const int Sc = cfg.n_samples, So = Sc + cfg.n_importance;
  const size_t n = size_t(n_rays) * So;
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  auto btc = cl::Buffer::from(rt, tc), bwc = cl::Buffer::from(rt, wc);
  // NaN / -1 first: an output the kernel never wrote shows.
  auto bt = cl::Buffer::from(rt, std::vector<float>(n, std::nanf("")));
  auto bx = cl::Buffer::from(rt, std::vector<float>(n * 3, std::nanf("")));
  auto bsrc = cl::Buffer::from(rt, std::vector<int>(n, -1));
  sampler.importance(bo, bd, n_rays, Sc, btc, bwc, jitter, 77, 5, bt, bx, bsrc).wait();
  return {bt.read_vec<float>(n), bx.read_vec<float>(n * 3), bsrc.read_vec<int>(n)};
}

// A fine sample of the wide kernel moves from the serial walk's by the two CDFs' difference
// (each a float sum of at most Sc + 1 positive terms normalised to 1: within 2 (Sc + 2) 2^-24
// of each other) over the probability of the bin it lands in, times that bin's width; near a
// bin edge it may land in the neighbour, so the bound takes the least probability and the
// widest bin of k - 1 .. k + 1, plus 4 ulp of t for the interpolation and the cap at the edge.
// Sorting moves no element by more than the largest move, so the merged samples of ray r are
// compared position by position against the largest bound of its fine samples.
std::vector<double> ray_bounds(int n_rays, int Sc, int Sf, float near, float far,
                               const std::vector<float>& tc, const std::vector<float>& wc,
                               const std::vector<float>& t_ref, const std::vector<int>& src_ref) {
  std::vector<double> bound(size_t(n_rays), 0.0);
  const double delta = 2.0 * (Sc + 2) * std::ldexp(1.0, -24);
  for (int r = 0; r < n_rays; ++r) {
    std::vector<double> edges(size_t(Sc) + 1, 0.0), p(size_t(Sc), 0.0);
    edges[0] = near, edges[size_t(Sc)] = far;
    for (int k = 1; k < Sc; ++k) edges[size_t(k)] = 0.5 * (tc[size_t(r) * Sc + k - 1] + tc[size_t(r) * Sc + k]);
    double total = 0;
    for (int k = 0; k < Sc; ++k) total += wc[size_t(r) * Sc + k] + 1e-5;
    for (int k = 0; k < Sc; ++k) p[size_t(k)] = (wc[size_t(r) * Sc + k] + 1e-5) / total;
    for (int i = 0; i < Sc + Sf; ++i) {
      const size_t s = size_t(r) * (Sc + Sf) + i;
      if (src_ref[s] < Sc) continue;
      const double t = t_ref[s];
      int k = int(std::upper_bound(edges.begin() + 1, edges.end() - 1, t) - edges.begin()) - 1;
      double p_min = 1.0, width = 0.0;
      for (int q = std::max(0, k - 1); q <= std::min(Sc - 1, k + 1); ++q) {
        p_min = std::min(p_min, p[size_t(q)]);
        width = std::max(width, edges[size_t(q) + 1] - edges[size_t(q)]);
      }
      bound[size_t(r)] =
          std::max(bound[size_t(r)], delta / p_min * width + 4.0 * std::ldexp(std::abs(t), -23));
    }
  }
  return bound;
}

struct Shape {
  int rays, coarse, fine;
};

void check_wide_importance(const std::vector<Shape>& shapes, const std::vector<int>& lane_counts,
                           const std::vector<bool>& jitters) {
  for (const Shape sh : shapes) {
    render::RenderConfig cfg;
    cfg.n_samples = sh.coarse;
    cfg.n_importance = sh.fine;
    const int n_rays = sh.rays, Sc = sh.coarse, Sf = sh.fine, So = Sc + Sf;
    std::vector<float> o, d;
    test::make_rays(n_rays, 3, o, d);
    // Sorted jittered coarse samples over [near, far]; weights: a peak, noise and empty bins.
    const float near = cfg.near_m * kScale, far = cfg.far_m * kScale, bin = (far - near) / Sc;
    const auto xi = test::make_uniform(size_t(n_rays) * Sc, 0.0f, 1.0f, 11);
    auto w = test::make_uniform(size_t(n_rays) * Sc, 0.0f, 0.004f, 12);
    std::vector<float> tc(size_t(n_rays) * Sc);
    for (int r = 0; r < n_rays; ++r)
      for (int k = 0; k < Sc; ++k) {
        tc[size_t(r) * Sc + k] = near + (float(k) + xi[size_t(r) * Sc + k]) * bin;
        if ((r + k) % 3 == 0) w[size_t(r) * Sc + k] = 0.0f;
        if (k == r % Sc) w[size_t(r) * Sc + k] = r % 4 == 0 ? 0.0f : 0.9f;  // some rays empty
      }
    for (const bool jitter : jitters) {
      CAPTURE(n_rays, Sc, Sf, jitter);
      const Merged cpu = importance(cl::cpu_profile(), cfg, n_rays, o, d, tc, w, jitter);
      std::vector<float> t_ref, x_ref;
      std::vector<int> src_ref;
      test::ref_sample_importance(n_rays, Sc, Sf, near, far, jitter, 77, 5, o, d, tc, w, t_ref,
                                  x_ref, &src_ref);
      REQUIRE(cpu.src == src_ref);  // the per-ray kernel is the reference's walk
      const auto bound = ray_bounds(n_rays, Sc, Sf, near, far, tc, w, t_ref, src_ref);
      for (const int lanes : lane_counts) {
        CAPTURE(lanes);
        const Merged wide = importance(lanes_profile(lanes), cfg, n_rays, o, d, tc, w, jitter);
        // Run to run: the same bits.
        const Merged again = importance(lanes_profile(lanes), cfg, n_rays, o, d, tc, w, jitter);
        CHECK(test::same_bits(wide.t, again.t));
        CHECK(test::same_bits(wide.x, again.x));
        CHECK(wide.src == again.src);
        size_t over = 0, unsorted = 0, not_perm = 0, coarse_moved = 0;
        double worst = 0;
        for (int r = 0; r < n_rays; ++r) {
          std::vector<int> seen(size_t(So), 0);
          for (int i = 0; i < So; ++i) {
            const size_t s = size_t(r) * So + i;
            const double err = std::abs(double(wide.t[s]) - t_ref[s]);
            worst = std::max(worst, err / bound[size_t(r)]);
            over += !(err <= bound[size_t(r)]);
            unsorted += i > 0 && !(wide.t[s - 1] <= wide.t[s]);
            const int src = wide.src[s];
            if (src < 0 || src >= So || seen[size_t(src)]++) ++not_perm;
            else if (src < Sc) coarse_moved += wide.t[s] != tc[size_t(r) * Sc + src];
            for (int c = 0; c < 3; ++c)  // x = o + t d of the sample's own t
              over += !(std::abs(wide.x[3 * s + c] - (o[3 * r + c] + wide.t[s] * d[3 * r + c])) <=
                        1e-6f);
          }
        }
        INFO("worst error / bound " << worst);
        CHECK(over == 0);
        CHECK(unsorted == 0);
        CHECK(not_perm == 0);
        CHECK(coarse_moved == 0);
        // The per-ray kernel's samples (the reference's walk, bit for bit on PoCL, measured
        // in a bound's 2 %; up to 5e-5 = 4 mm apart, in the bins left almost empty) likewise.
        size_t over_cpu = 0;
        for (size_t s = 0; s < cpu.t.size(); ++s)
          over_cpu += !(std::abs(double(wide.t[s]) - cpu.t[s]) <= bound[s / size_t(So)]);
        CHECK(over_cpu == 0);
      }
    }
  }
}
}  // namespace

// One coarse bin, bins fewer than the lanes, the render tests' 32 + 24, the quick preset's
// 64 + 32; ray counts that leave a work-group part empty; 2, 32 (the gpu profile's) and 64
// lanes per ray.
TEST_CASE("Wide importance samples equal the per-ray kernel's within the CDF's rounding",
          "[render][sample][sample_wide]") {
  check_wide_importance({{3, 1, 5}, {37, 5, 40}, {21, 32, 24}, {9, 64, 32}}, {2, 32, 64},
                        {true, false});
}

// The same on a few rays at the gpu profile's 32 lanes (oclgrind_render).
TEST_CASE("Wide importance samples on a small case", "[render][sample][sample_wide][small]") {
  check_wide_importance({{3, 20, 12}}, {32}, {true});
}

TEST_CASE("Wide surface samples equal the per-ray kernel's and the reference",
          "[render][surface][sample_wide]") {
  auto& rt = test::runtime();
  render::RenderConfig cfg;  // test_surface.cpp's: 12 free, 10 band and 3 behind samples
  cfg.surface_free_samples = 12;
  cfg.surface_band_samples = 10;
  cfg.surface_behind_samples = 3;
  cfg.surface_band_start_m = 1.0f;
  cfg.surface_band_end_m = 0.25f;
  cfg.surface_anneal_steps = 100;
  cfg.surface_behind_m = 2.0f;
  const int n_rays = 131;
  std::vector<float> o, d;
  test::make_rays(n_rays, 4, o, d);
  // Targets: returns at ranges across the ray, some without a return (label 0).
  const auto rng = test::make_uniform(size_t(n_rays), 0.05f, 0.95f, 13);
  std::vector<float> target;
  for (int r = 0; r < n_rays; ++r) {
    target.push_back(rng[size_t(r)]);
    target.push_back(0.3f);
    target.push_back(r % 5 == 0 ? 0.0f : 1.0f);
  }
  auto bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d);
  auto btarget = cl::Buffer::from(rt, target);
  auto run = [&](const cl::DeviceProfile& p, bool jitter) {
    test::ProfileScope scope(p);
    render::SurfaceSampler sampler(rt, cfg, kScale);
    const size_t n = size_t(n_rays) * sampler.samples();
    auto bt = cl::Buffer::from(rt, std::vector<float>(n, std::nanf("")));
    auto bx = cl::Buffer::from(rt, std::vector<float>(n * 3, std::nanf("")));
    sampler.sample(bo, bd, btarget, n_rays, jitter, 0x5eedull, 40, bt, bx).wait();
    return std::make_pair(bt.read_vec<float>(n), bx.read_vec<float>(n * 3));
  };
  for (const bool jitter : {true, false}) {
    CAPTURE(jitter);
    const auto cpu = run(cl::cpu_profile(), jitter);
    const auto wide = run(cl::gpu_profile(), jitter);
    const auto again = run(cl::gpu_profile(), jitter);
    CHECK(test::same_bits(wide.first, again.first));
    CHECK(test::same_bits(wide.second, again.second));
    // The same operations on the same values as the per-ray kernel (a device may still contract
    // them differently): a few ulp of t, and the reference's 1e-6 (render tests).
    CHECK(test::sym_rel_err(wide.first, cpu.first, 1e-3) <= 1e-6);
    CHECK(test::sym_rel_err(wide.second, cpu.second, 1e-3) <= 1e-6);
    render::SurfaceSampler sampler(rt, cfg, kScale);
    std::vector<float> t_ref, x_ref;
    test::ref_sample_surface(n_rays, 12, 10, 3, sampler.near(), sampler.far(),
                             sampler.half_width(40), cfg.surface_behind_m * kScale, jitter,
                             0x5eedull, 40, o, d, target, t_ref, x_ref);
    CHECK(test::max_abs_err(wide.first, t_ref) < 1e-6);
    CHECK(test::max_abs_err(wide.second, x_ref) < 1e-6);
  }
}
