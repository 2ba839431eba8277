// The U-Net layers of LiDAR4D's ray-drop refinement (max pool, bilinear ×2 upsampling into a
// padded concatenation, channel copy, sigmoid + BCE, box mask): device vs host reference,
// finite differences of the device forward for every backward, accumulation, untouched
// channels, and refused shapes naming the bad value.
#include <catch2/catch.hpp>

#include <cmath>

#include "conv/bce_loss.hpp"
#include "conv/box_mask.hpp"
#include "conv/channel_copy.hpp"
#include "conv/max_pool.hpp"
#include "conv/upsample.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "support/test_device.hpp"
#include "unet_reference.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

namespace {
using test::uniform;
// Distinct values 0.01·k (k a random permutation), so no window has ties within 2 FD steps.
std::vector<float> distinct(size_t n, uint64_t seed) {
  std::vector<float> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = 0.01f * float(i) - 0.005f * float(n);
  Rng r(seed);
  for (size_t i = n; i > 1; --i) std::swap(v[i - 1], v[r.below(uint32_t(i))]);
  return v;
}
double dot_on(const std::vector<float>& a, const std::vector<float>& b, int c_lo, int c_hi,
              int cs) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const int c = int(i % size_t(cs));
    if (c >= c_lo && c < c_hi) s += double(a[i]) * b[i];
  }
  return s;
}
// Central differences of L(x) at every `stride`-th entry whose channel is < c (stride cs).
template <typename L>
std::vector<float> fd_grad(std::vector<float> x, int c, int cs, size_t stride, float h, L&& loss,
                           std::vector<size_t>* where) {
  std::vector<float> g;
  for (size_t k = 0; k < x.size(); k += stride) {
    if (int(k % size_t(cs)) >= c) continue;
    const float x0 = x[k];
    x[k] = x0 + h;
    const double lp = loss(x);
    x[k] = x0 - h;
    const double lm = loss(x);
    x[k] = x0;
    g.push_back(float((lp - lm) / (2.0 * h)));
    where->push_back(k);
  }
  return g;
}
std::vector<float> pick(const std::vector<float>& v, const std::vector<size_t>& at) {
  std::vector<float> out;
  for (size_t k : at) out.push_back(v[k]);
  return out;
}
}  // namespace

TEST_CASE("2x2 max pooling matches the reference and finite differences", "[conv][maxpool]") {
  auto& rt = test::runtime();
  conv::MaxPool2x2 pool(rt);
  for (const conv::PoolShape s :
       {conv::PoolShape{2, 9, 13, 3, 3, 3}, conv::PoolShape{1, 8, 6, 5, 16, 16}}) {
    const auto in = distinct(size_t(s.n) * s.h * s.w * s.in_cs, 3);
    const size_t out_n = size_t(s.n) * s.out_h() * s.out_w() * s.out_cs;
    const std::vector<float> out0(out_n, 5.0f);
    const auto d_out = uniform(out_n, -1.0f, 1.0f, 4);
    const auto d_in0 = uniform(in.size(), -1.0f, 1.0f, 5);
    auto b_in = cl::Buffer::from(rt, in), b_out = cl::Buffer::from(rt, out0);
    auto b_dout = cl::Buffer::from(rt, d_out), b_din = cl::Buffer::from(rt, d_in0);
    pool.forward(s, b_in, b_out);
    // Bit equality, exact by construction: a selection, and one addition when accumulating.
    CHECK(b_out.read_all<float>() == test::ref::maxpool2_fwd(s, in, out0));
    for (bool acc : {false, true}) {
      b_din.write_vec(d_in0);
      pool.backward(s, b_in, b_dout, b_din, acc);
      CHECK(b_din.read_all<float>() == test::ref::maxpool2_bwd(s, in, d_out, d_in0, acc));
    }
    // Ties (ReLU outputs are often 0): the gradient goes to the first maximum only.
    auto ties = uniform(in.size(), 0.0f, 1.0f, 16);
    for (auto& v : ties) v = v < 0.7f ? 0.0f : 1.0f;
    b_in.write_vec(ties);
    pool.backward(s, b_in, b_dout, b_din, false);
    CHECK(b_din.read_all<float>() == test::ref::maxpool2_bwd(s, ties, d_out, d_in0, false));
    b_in.write_vec(in);
    pool.backward(s, b_in, b_dout, b_din, false);
    const auto din = b_din.read_all<float>();
    std::vector<size_t> at;
    const auto fd = fd_grad(in, s.c, s.in_cs, 2, 2e-3f, [&](const std::vector<float>& x) {
      b_in.write_vec(x);
      pool.forward(s, b_in, b_out);
      return dot_on(b_out.read_all<float>(), d_out, 0, s.c, s.out_cs);
    }, &at);
    REQUIRE(fd.size() > 50);
    CHECK(test::max_sym_rel_err(fd, pick(din, at), 1e-1) < 1e-3);
  }
  cl::Buffer b(rt, 64);
  REQUIRE_THROWS_WITH(pool.forward(conv::PoolShape{1, 4, 1, 1, 1, 1}, b, b),
                      Catch::Contains("w = 1"));
  REQUIRE_THROWS_WITH(pool.forward(conv::PoolShape{1, 8, 8, 1, 1, 1}, b, b),
                      Catch::Contains("'in'"));
}

TEST_CASE("Bilinear x2 upsampling into a padded concatenation matches the reference and "
          "finite differences", "[conv][upsample]") {
  auto& rt = test::runtime();
  conv::Upsample2x up(rt);
  // Exact 2h x 2w; a target one larger (33 from 16, LiDAR4D's pad); a 1-pixel-high input;
  // channels written at an offset of a wider target.
  for (const conv::UpsampleShape s :
       {conv::UpsampleShape{2, 4, 5, 3, 3, 8, 10, 3, 0},
        conv::UpsampleShape{1, 5, 2, 2, 4, 11, 5, 8, 5},  // w = 2: the widest tap range
        conv::UpsampleShape{1, 1, 4, 16, 16, 3, 9, 32, 16}}) {
    const auto in = uniform(size_t(s.n) * s.h * s.w * s.in_cs, -1.0f, 1.0f, 6);
    const size_t out_n = size_t(s.n) * s.th * s.tw * s.out_cs;
    const auto out0 = uniform(out_n, -1.0f, 1.0f, 7);
    const auto d_out = uniform(out_n, -1.0f, 1.0f, 8);
    const auto d_in0 = uniform(in.size(), -1.0f, 1.0f, 9);
    auto b_in = cl::Buffer::from(rt, in), b_out = cl::Buffer::from(rt, out0);
    auto b_dout = cl::Buffer::from(rt, d_out), b_din = cl::Buffer::from(rt, d_in0);
    up.forward(s, b_in, b_out);
    const auto out = b_out.read_all<float>();
    const auto ref = test::ref::upsample2_fwd(s, in, out0);
    CHECK(test::max_abs_err(out, ref) < 1e-6);
    for (size_t i = 0; i < out.size(); ++i) {  // channels outside [dst_off, dst_off + c) untouched
      const int c = int(i % size_t(s.out_cs));
      if (c < s.dst_off || c >= s.dst_off + s.c) REQUIRE(out[i] == out0[i]);
    }
    for (bool acc : {false, true}) {
      b_din.write_vec(d_in0);
      up.backward(s, b_dout, b_din, acc);
      const auto ref_din = test::ref::upsample2_bwd(s, d_out, d_in0, acc);
      CHECK(test::max_abs_err(b_din.read_all<float>(), ref_din) < 1e-5);
    }
    up.backward(s, b_dout, b_din, false);
    const auto din = b_din.read_all<float>();
    std::vector<size_t> at;
    const auto fd = fd_grad(in, s.c, s.in_cs, 1, 1e-2f, [&](const std::vector<float>& x) {
      b_in.write_vec(x);
      up.forward(s, b_in, b_out);
      return dot_on(b_out.read_all<float>(), d_out, s.dst_off, s.dst_off + s.c, s.out_cs);
    }, &at);
    REQUIRE(fd.size() >= 12);
    CHECK(test::max_sym_rel_err(fd, pick(din, at), 1e-1) < 1e-3);
  }
  cl::Buffer b(rt, 4096);
  REQUIRE_THROWS_WITH(up.forward(conv::UpsampleShape{1, 4, 4, 1, 1, 7, 8, 1, 0}, b, b),
                      Catch::Contains("target 7 x 8"));
  REQUIRE_THROWS_WITH(up.forward(conv::UpsampleShape{1, 4, 4, 4, 4, 8, 8, 6, 3}, b, b),
                      Catch::Contains("dst_off = 3"));
}

TEST_CASE("Channel copy (skip concatenation and its split) matches the reference",
          "[conv][concat]") {
  auto& rt = test::runtime();
  conv::ChannelCopy copy(rt);
  const conv::ChannelCopyShape s{37, 5, 16, 2, 24, 11};
  const auto src = uniform(size_t(s.pixels) * s.src_cs, -1.0f, 1.0f, 10);
  const auto dst0 = uniform(size_t(s.pixels) * s.dst_cs, -1.0f, 1.0f, 11);
  auto b_src = cl::Buffer::from(rt, src), b_dst = cl::Buffer::from(rt, dst0);
  for (bool acc : {false, true}) {
    b_dst.write_vec(dst0);
    copy.run(s, b_src, b_dst, acc);
    // Bit equality, exact by construction: a copy, and one addition when accumulating.
    CHECK(b_dst.read_all<float>() == test::ref::copy_channels(s, src, dst0, acc));
  }
  // The split is the transpose of the copy: <copy(x), g> = <x, split(g)>.
  const auto g = uniform(dst0.size(), -1.0f, 1.0f, 12);
  const conv::ChannelCopyShape back{s.pixels, s.c, s.dst_cs, s.dst_off, s.src_cs, s.src_off};
  const std::vector<float> zeros_src(src.size(), 0.0f), zeros_dst(dst0.size(), 0.0f);
  const auto fwd = test::ref::copy_channels(s, src, zeros_dst, false);
  auto b_g = cl::Buffer::from(rt, g), b_x = cl::Buffer::from(rt, zeros_src);
  copy.run(back, b_g, b_x, false);
  const double lhs = dot_on(fwd, g, 0, 1, 1), rhs = dot_on(src, b_x.read_all<float>(), 0, 1, 1);
  CHECK(std::fabs(lhs - rhs) < 1e-4);
  REQUIRE_THROWS_WITH(copy.run({4, 5, 16, 12, 16, 0}, b_src, b_dst, false),
                      Catch::Contains("src_off = 12"));
}

TEST_CASE("Sigmoid + BCE matches the reference and finite differences", "[conv][bce]") {
  auto& rt = test::runtime();
  conv::BceWithLogits bce(rt);
  // One chunk, a padded layout, and several chunks (600 pixels, 256 per chunk).
  for (const auto& shape : {std::pair{37, 1}, std::pair{41, 16}, std::pair{600, 3}}) {
    const int count = shape.first, cs = shape.second;  // a lambda below captures them
    auto logits = uniform(size_t(count) * cs, -4.0f, 4.0f, 13);
    auto target = uniform(size_t(count), 0.0f, 1.0f, 14);
    for (size_t i = 0; i < target.size(); i += 2) target[i] = target[i] < 0.5f ? 0.0f : 1.0f;
    auto b_z = cl::Buffer::from(rt, logits), b_y = cl::Buffer::from(rt, target);
    auto b_d = cl::Buffer::from(rt, std::vector<float>(logits.size(), 9.0f));
    auto b_l = cl::Buffer::from(rt, std::vector<float>(3, 7.0f));
    bce.loss_grad(b_z, count, cs, b_y, b_d, b_l, 1);
    std::vector<float> d_ref;
    const double l_ref = test::ref::bce_with_logits(logits, count, cs, target, d_ref);
    const auto l = b_l.read_all<float>();
    CHECK(l[0] == 7.0f);
    CHECK(l[2] == 7.0f);
    CHECK(std::fabs(l[1] - l_ref) < 1e-5 * l_ref);
    const auto d = b_d.read_all<float>();
    CHECK(test::max_abs_err(d, d_ref) < 1e-7);  // padding channels 0 as in the reference
    auto b_p = cl::Buffer::from(rt, std::vector<float>(size_t(count), 0.0f));
    bce.sigmoid(b_z, count, cs, b_p);
    CHECK(test::max_abs_err(b_p.read_all<float>(), test::ref::sigmoid(logits, count, cs)) < 1e-6);
    if (count > 100) continue;  // FD of a float mean: small counts only
    std::vector<size_t> at;
    const auto fd = fd_grad(logits, 1, cs, 1, 1e-2f, [&](const std::vector<float>& z) {
      b_z.write_vec(z);
      bce.loss_grad(b_z, count, cs, b_y, b_d, b_l, 0);
      return double(b_l.read_vec<float>(1)[0]);
    }, &at);
    REQUIRE(fd.size() == size_t(count));
    CHECK(test::max_sym_rel_err(fd, pick(d, at), 1e-2) < 2e-3);
  }
  REQUIRE(conv::BceWithLogits::chunks(600) == 3);
  REQUIRE(conv::BceWithLogits::chunks(1 << 20) == 1024);
  cl::Buffer b(rt, 64);
  REQUIRE_THROWS_WITH(bce.loss_grad(b, 0, 1, b, b, b, 0), Catch::Contains("count = 0"));
  REQUIRE_THROWS_WITH(bce.loss_grad(b, 16, 1, b, b, b, 16), Catch::Contains("'losses'"));
}

TEST_CASE("Box mask matches the reference; no boxes is the scaling alone", "[conv][box_mask]") {
  auto& rt = test::runtime();
  conv::BoxMask mask(rt);
  const conv::BoxMaskShape s{2, 7, 11, 3, 3, 4};
  const auto in = uniform(size_t(s.n) * s.h * s.w * s.in_cs, 0.0f, 1.0f, 15);
  const std::vector<float> out0(size_t(s.n) * s.h * s.w * s.out_cs, 5.0f), scale{1.0f, 0.5f, 0.25f};
  const std::vector<std::array<int, 4>> all{
      {9, 9, 9, 9}, {1, 2, 3, 5}, {0, 8, 7, 11}, {5, 0, 7, 1}};
  std::vector<int> flat;
  for (const auto& b : all) flat.insert(flat.end(), b.begin(), b.end());
  auto b_in = cl::Buffer::from(rt, in), b_out = cl::Buffer::from(rt, out0);
  auto b_s = cl::Buffer::from(rt, scale), b_b = cl::Buffer::from(rt, flat);
  mask.run(s, b_s, b_b, 1, 3, b_in, b_out);  // the last three boxes
  // Bit equality below, exact by construction: integer box tests and one multiplication.
  const std::vector<std::array<int, 4>> used(all.begin() + 1, all.end());
  CHECK(b_out.read_all<float>() == test::ref::box_mask(s, scale, used, in, out0));
  b_out.write_vec(out0);
  mask.run(s, b_s, b_b, 0, 0, b_in, b_out);
  CHECK(b_out.read_all<float>() == test::ref::box_mask(s, scale, {}, in, out0));
  REQUIRE_THROWS_WITH(mask.run(s, b_s, b_b, 2, 3, b_in, b_out), Catch::Contains("boxes [2, +3)"));
  REQUIRE_THROWS_WITH(mask.run({1, 4, 4, 3, 2, 3}, b_s, b_b, 0, 0, b_in, b_out),
                      Catch::Contains("in_cs = 2"));
}
