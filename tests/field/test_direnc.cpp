// Direction frequency encoding and LiDAR-head input: device vs host reference, and finite
// differences of the device forward for d_dir.
#include <catch2/catch.hpp>

#include <cmath>

#include "cl/device_profile.hpp"
#include "core/rng.hpp"
#include "field/dir_encoding.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
using test::uniform;
std::vector<float> unit_dirs(int n, uint64_t seed) {
  Rng r(seed);
  std::vector<float> d;
  for (int i = 0; i < n; ++i) {
    double v[3] = {r.normal(), r.normal(), r.normal()};
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double c : v) d.push_back(float(c / l));
  }
  return d;
}
}  // namespace

// Under the runtime's profile: the cpu profile's per-ray loops in `field`, the gpu profile's
// (ray, frequency) kernels (ray_work_items > 1) in `field_direnc_gpu_profile` and Oclgrind.
TEST_CASE("direction encoding matches the reference and finite differences",
          "[field][direnc]") {
  auto& rt = test::runtime();
  field::DirEncoding de(rt);
  REQUIRE(de.enc_dim() == 72);
  REQUIRE(de.head_width() == 87);
  const int r = 500;
  const auto dir = unit_dirs(r, 1);
  const auto d_enc = uniform(size_t(r) * 72, -1.0f, 1.0f, 2);
  auto b_dir = cl::Buffer::from(rt, dir), b_denc = cl::Buffer::from(rt, d_enc);
  cl::Buffer b_enc(rt, size_t(r) * 72 * 4), b_ddir(rt, size_t(r) * 12);
  de.forward(b_dir, r, b_enc);
  de.backward(b_dir, r, b_denc, b_ddir);
  const auto enc = b_enc.read_vec<float>(size_t(r) * 72);
  const auto ddir = b_ddir.read_vec<float>(size_t(r) * 3);
  // Arguments up to 2^11: float argument rounding alone is 2^11·6e-8 ≈ 1.2e-4 in sin/cos.
  CHECK(test::max_abs_err(enc, test::ref::direnc_fwd(dir, 12)) < 2e-4);
  const auto ddir_ref = test::ref::direnc_bwd(dir, 12, d_enc);
  CHECK(test::max_abs_err(ddir, ddir_ref) < 2e-4 * 2048 * 6);
  CHECK(test::max_sym_rel_err(ddir, ddir_ref, 10.0) < 1e-3);

  // Finite differences with 4 frequencies (highest 8): smooth on the scale of h.
  field::DirEncoding de4(rt, 4);
  cl::Buffer b_enc4(rt, size_t(r) * 24 * 4);
  const auto rr = uniform(size_t(r) * 24, -1.0f, 1.0f, 3);  // L = Σ rr · enc
  auto b_rr = cl::Buffer::from(rt, rr);
  de4.backward(b_dir, r, b_rr, b_ddir);
  const auto an_all = b_ddir.read_vec<float>(size_t(r) * 3);
  auto loss = [&](const std::vector<float>& d) {
    b_dir.write_vec(d);
    de4.forward(b_dir, r, b_enc4);
    const auto e = b_enc4.read_vec<float>(size_t(r) * 24);
    double s = 0;
    for (size_t k = 0; k < e.size(); ++k) s += double(e[k]) * rr[k];
    return s;
  };
  const float h = 1e-3f;
  std::vector<float> fd, an;
  for (size_t k = 0; k < dir.size(); k += 5) {
    auto p = dir, m = dir;
    p[k] += h;
    m[k] -= h;
    fd.push_back(float((loss(p) - loss(m)) / (2.0 * h)));
    an.push_back(an_all[k]);
  }
  // Truncation h²/6·Σ 8³ ≈ 1e-4, rounding of L (~1e-5 abs) / h ≈ 1e-2 absolute.
  CHECK(test::max_sym_rel_err(fd, an, 1.0) < 1e-2);
}

// The gpu profile's kernels against the cpu profile's on one device, at frequency counts whose
// lanes are 1, 4, 16 and 32 and ray counts that leave a work-group part empty: the forward is
// the same sincos of the same exact arguments (within the host tolerance of the reference
// test: a device may vectorise them differently), the backward the same terms summed in a tree
// rather than in order, so within float rounding of the sum (a few ulp of Σ|term| ≤ 2^F·6);
// and each is the same bits from run to run.
TEST_CASE("direction encoding's wide kernels match the per-ray ones and repeat bit for bit",
          "[field][direnc][direnc_wide]") {
  auto& rt = test::runtime();
  for (const int n_freq : {1, 3, 12, 20}) {
    for (const int r : {1, 37, 130}) {
      INFO("n_freq " << n_freq << ", rays " << r);
      const int ed = 6 * n_freq;
      const auto dir = unit_dirs(r, 7);
      const auto d_enc = uniform(size_t(r) * ed, -1.0f, 1.0f, 8);
      auto b_dir = cl::Buffer::from(rt, dir), b_denc = cl::Buffer::from(rt, d_enc);
      cl::Buffer b_enc(rt, size_t(r) * ed * 4), b_ddir(rt, size_t(r) * 12);
      auto run = [&](const cl::DeviceProfile& p) {
        test::ProfileScope scope(p);
        field::DirEncoding de(rt, n_freq);
        b_enc.write_vec(std::vector<float>(size_t(r) * ed, std::nanf("")));
        b_ddir.write_vec(std::vector<float>(size_t(r) * 3, std::nanf("")));
        de.forward(b_dir, r, b_enc);
        de.backward(b_dir, r, b_denc, b_ddir);
        return std::make_pair(b_enc.read_vec<float>(size_t(r) * ed),
                              b_ddir.read_vec<float>(size_t(r) * 3));
      };
      const auto cpu = run(cl::cpu_profile());
      const auto gpu = run(cl::gpu_profile());
      const auto again = run(cl::gpu_profile());
      CHECK(test::same_bits(gpu.first, again.first));
      CHECK(test::same_bits(gpu.second, again.second));
      // The same exact arguments: sin/cos within OpenCL's 4 ulp of each other at worst.
      CHECK(test::sym_rel_err(gpu.first, cpu.first, 1.0) <= 1e-6);
      // Term k is at most 2^k·2 in magnitude, so Σ|term| < 2^F·2 = floor: the two orders' sums
      // differ by at most (F − 1 + log2 lanes)·2^-24 of it (< 1.5e-6 at F = 20), the
      // reference (double) by that plus 4 ulp of each term.
      const double floor = std::ldexp(1.0, n_freq) * 2.0;
      CHECK(test::sym_rel_err(gpu.second, cpu.second, floor) <= 2e-6);
      CHECK(test::sym_rel_err(gpu.second, test::ref::direnc_bwd(dir, n_freq, d_enc), floor) <=
            3e-6);
    }
  }
}

TEST_CASE("head input assembly and its backward split", "[field][direnc]") {
  auto& rt = test::runtime();
  for (int n_freq : {12, 3}) {  // 72 columns (8-wide vector path) and 18 (2-wide path)
    INFO("n_freq " << n_freq);
    field::DirEncoding de(rt, n_freq);
    const int ed = de.enc_dim(), hw = de.head_width();
    const int rays = 37, s = 13, n = rays * s;
    const auto dens = uniform(size_t(n) * 16, -1.0f, 1.0f, 4);
    const auto enc = uniform(size_t(rays) * ed, -1.0f, 1.0f, 5);
    const auto d_head = uniform(size_t(n) * hw, -1.0f, 1.0f, 6);
    auto b_dens = cl::Buffer::from(rt, dens), b_enc = cl::Buffer::from(rt, enc);
    auto b_dhead = cl::Buffer::from(rt, d_head);
    cl::Buffer b_head(rt, size_t(n) * hw * 4), b_denc(rt, size_t(rays) * ed * 4);
    auto b_ddens = cl::Buffer::from(rt, std::vector<float>(size_t(n) * 16, 5.0f));
    de.head_input_forward(b_dens, b_enc, rays, s, b_head);
    de.head_input_backward(b_dhead, rays, s, b_ddens, b_denc);
    // Bit equality, exact by construction on any device: the forward and d_dens are copies,
    // d_enc sums in the kernel's order with additions only (nothing to contract into an FMA).
    CHECK(b_head.read_vec<float>(size_t(n) * hw) ==
          test::ref::head_input_fwd(dens, enc, rays, s, 15, 1, 16, ed));
    const auto ddens = b_ddens.read_vec<float>(size_t(n) * 16);
    const auto denc = b_denc.read_vec<float>(size_t(rays) * ed);
    size_t bad = 0;
    for (int i = 0; i < n; ++i) {
      bad += ddens[size_t(i) * 16] != 5.0f;  // density column untouched
      for (int j = 0; j < 15; ++j)
        bad += ddens[size_t(i) * 16 + 1 + j] != d_head[size_t(i) * hw + j];
    }
    CHECK(bad == 0);
    std::vector<float> denc_ref(size_t(rays) * ed, 0.0f);
    for (int r = 0; r < rays; ++r)
      for (int k = 0; k < ed; ++k) {
        float acc = 0.0f;  // the kernel's order: samples in sequence, in float
        for (int t = 0; t < s; ++t) acc += d_head[(size_t(r) * s + t) * hw + 15 + k];
        denc_ref[size_t(r) * ed + k] = acc;
      }
    CHECK(test::max_abs_err(denc, denc_ref) == 0.0);
  }
}
