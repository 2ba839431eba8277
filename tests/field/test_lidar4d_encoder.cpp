// LiDAR4D's composite encoder (runtime/field/lidar4d_encoder.hpp): the composite forward equals
// its parts' host references blended as method.md §2 says (inside the sequence, at its ends,
// blending off), finite differences of the device forward for every parameter kind (planes,
// hashes, flow) and the positions, bit-identical repeats, and refusals.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "field/lidar4d_encoder.hpp"
#include "lidar4d_reference.hpp"
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
// init_params, then hash tables of order 1 (their ±1e-4 init would hide them) and
// non-constant time planes (they start at 1).
std::vector<float> params_for(field::Lidar4DEncoder& enc, uint64_t seed) {
  std::vector<float> p(enc.n_params());
  enc.init_params(p, 0, seed);
  const auto& o = enc.offsets();
  const auto r = uniform(p.size(), -1.0f, 1.0f, seed + 100);
  for (size_t k = o.static_hash; k < o.flow + enc.flow().mlp_offset(); ++k) p[k] = r[k];
  for (size_t k = o.planes; k < o.static_hash; ++k) p[k] += 0.3f * r[k];
  return p;
}
test::ref::TimeState state(float t, float dt, bool prev, bool next) {
  test::ref::TimeState s;
  s.t = t;
  s.dt = dt;
  s.has_prev = prev;
  s.has_next = next;
  return s;
}
}  // namespace

TEST_CASE("lidar4d encoder forward equals its parts blended (host reference)",
          "[field][lidar4d]") {
  auto& rt = test::runtime();
  const int n = 257;
  const auto x = uniform(size_t(n) * 3, -0.8f, 0.8f, 2);
  struct Case {
    const char* name;
    test::ref::TimeState ts;
    bool blend;
  };
  for (const Case& c : {Case{"inside", state(0.5f, 0.25f, true, true), true},
                        Case{"first frame", state(0.0f, 0.25f, false, true), true},
                        Case{"last frame", state(1.0f, 0.25f, true, false), true},
                        Case{"between frames", state(0.4f, 0.2f, true, true), true},
                        Case{"blend off", state(0.5f, 0.25f, true, true), false}}) {
    SECTION(c.name) {
      auto cfg = test::ref::small_lidar4d_config(0.05f);
      cfg.blend = c.blend;
      field::Lidar4DEncoder enc(rt, cfg);
      REQUIRE(enc.width() == 2 * 2 * 2 + 3 * 2 + 2 * 2);  // planes 2·(S·F) + hash 6 + time 4
      REQUIRE(enc.parts() == std::vector<int>{10, 8});
      const auto params = params_for(enc, 11);
      enc.set_time(c.ts.t, c.ts.dt, c.ts.has_prev, c.ts.has_next);
      const size_t off = 5;
      std::vector<float> padded(off, 0.0f);
      padded.insert(padded.end(), params.begin(), params.end());
      auto b_p = cl::Buffer::from(rt, padded), b_x = cl::Buffer::from(rt, x);
      cl::Buffer b_enc(rt, size_t(n) * size_t(enc.width()) * 4);
      enc.forward(b_p, off, b_x, n, b_enc);
      const auto got = b_enc.read_vec<float>(size_t(n) * size_t(enc.width()));
      const auto want = test::ref::lidar4d_fwd(cfg, enc.offsets(), params, x, c.ts);
      CHECK(test::max_sym_rel_err(got, want, 1e-3) < 1e-4);
      if (c.blend) {  // the flow moved the neighbours: the blend differs from f(x, t) alone
        auto still = cfg;
        still.blend = false;
        const auto alone = test::ref::lidar4d_fwd(still, enc.offsets(), params, x, c.ts);
        CHECK(test::max_abs_err(alone, want) > 1e-3);
      }
    }
  }
}

TEST_CASE("lidar4d encoder gradients agree with finite differences of the device forward",
          "[field][lidar4d][fd]") {
  auto& rt = test::runtime();
  const auto cfg = test::ref::small_lidar4d_config(0.05f);
  field::Lidar4DEncoder enc(rt, cfg);
  enc.set_frame(2, 0, 5);  // t = 0.5, both neighbours
  const int n = 24, w = enc.width();
  auto params = params_for(enc, 21);
  const auto x = uniform(size_t(n) * 3, -0.8f, 0.8f, 22);
  const auto r = uniform(size_t(n) * size_t(w), -1.0f, 1.0f, 23);  // L = Σ r · enc
  auto b_p = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_enc(rt, size_t(n) * size_t(w) * 4), b_dx(rt, size_t(n) * 12);
  auto b_g = cl::Buffer::from(rt, std::vector<float>(params.size(), 7.0f));
  enc.forward(b_p, 0, b_x, n, b_enc);
  enc.backward(b_p, 0, b_x, n, b_r, b_g, 0, &b_dx);
  const auto grad = b_g.read_vec<float>(params.size());
  const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& xs) {
    b_p.write_vec(p);
    b_x.write_vec(xs);
    enc.forward(b_p, 0, b_x, n, b_enc);
    return dot(b_enc.read_vec<float>(size_t(n) * size_t(w)), r);
  };
  const auto& o = enc.offsets();
  auto check_range = [&](size_t begin, size_t end, float h, double tol, size_t want) {
    std::vector<float> fd, an;
    const size_t stride = std::max<size_t>(1, (end - begin) / 400);
    for (size_t k = begin; k < end && fd.size() < 60; k += stride) {
      if (grad[k] == 0.0f) continue;
      auto pp = params, pm = params;
      pp[k] += h;
      pm[k] -= h;
      fd.push_back(float((loss(pp, x) - loss(pm, x)) / (2.0 * h)));
      an.push_back(grad[k]);
    }
    CHECK(fd.size() >= want);
    CHECK(test::max_sym_rel_err(fd, an, 1e-2) < tol);
  };
  // L is linear in one entry of a hash table or one plane (a factor of a product), at the
  // point's own time and at both neighbours: large steps are exact up to rounding.
  SECTION("planes") { check_range(o.planes, o.static_hash, 0.25f, 1e-3, 30); }
  SECTION("static hash") { check_range(o.static_hash, o.time_hash, 0.25f, 1e-3, 30); }
  SECTION("time hash") { check_range(o.time_hash, o.flow, 0.25f, 1e-3, 30); }
  // The flow moves the neighbours' sampling points: smooth between cell faces only.
  SECTION("flow") { check_range(o.flow, o.end, 1e-3f, 3e-2, 30); }
  SECTION("positions") {
    const float h = 1e-3f;
    int agree = 0;
    for (size_t k = 0; k < x.size(); ++k) {
      auto xp = x, xm = x;
      xp[k] += h;
      xm[k] -= h;
      const float f = float((loss(params, xp) - loss(params, xm)) / (2.0 * h));
      agree += test::max_sym_rel_err({f}, {dx[k]}, 1e-1) < 2e-2;
    }
    CHECK(agree >= int(x.size()) * 9 / 10);
  }
}

TEST_CASE("lidar4d encoder: bit-identical repeats; blend off leaves the flow untrained",
          "[field][lidar4d]") {
  auto& rt = test::runtime();
  const auto cfg = test::ref::small_lidar4d_config(0.05f);
  const int n = 500;
  const auto x = uniform(size_t(n) * 3, -0.9f, 0.9f, 31);
  auto run = [&](const field::Lidar4DEncoderConfig& c) {
    field::Lidar4DEncoder enc(rt, c);
    enc.set_frame(3, 1, 6);
    const auto params = params_for(enc, 32);
    const auto r = uniform(size_t(n) * size_t(enc.width()), -1.0f, 1.0f, 33);
    auto b_p = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
    auto b_r = cl::Buffer::from(rt, r);
    cl::Buffer b_enc(rt, size_t(n) * size_t(enc.width()) * 4), b_dx(rt, size_t(n) * 12);
    auto b_g = cl::Buffer::from(rt, std::vector<float>(params.size(), 7.0f));
    enc.forward(b_p, 0, b_x, n, b_enc);
    enc.backward(b_p, 0, b_x, n, b_r, b_g, 0, &b_dx);
    auto out = b_enc.read_vec<float>(size_t(n) * size_t(enc.width()));
    const auto g = b_g.read_vec<float>(params.size());
    const auto d = b_dx.read_vec<float>(size_t(n) * 3);
    out.insert(out.end(), g.begin(), g.end());
    out.insert(out.end(), d.begin(), d.end());
    return std::make_pair(out, enc.offsets());
  };
  const auto a = run(cfg), b = run(cfg);
  CHECK(a.first == b.first);
  auto off = cfg;
  off.blend = false;
  const auto c = run(off);
  const size_t w = size_t(n) * 18, f0 = w + c.second.flow, f1 = w + c.second.end;
  bool flow_zero = true, flow_moves = false;
  for (size_t k = f0; k < f1; ++k) {
    flow_zero = flow_zero && c.first[k] == 0.0f;
    flow_moves = flow_moves || a.first[k] != 0.0f;
  }
  CHECK(flow_zero);   // overwritten with zero, not left at 7
  CHECK(flow_moves);  // with blending, the flow receives gradients
}

TEST_CASE("lidar4d encoder refuses bad configs and times, naming them", "[field][lidar4d]") {
  auto refused = [](const char* text, const char* key) {
    try {
      field::Lidar4DEncoderConfig::from_json(Json::parse(text), "lidar4d");
      FAIL("accepted " << text);
    } catch (const ConfigError& e) {
      CHECK_THAT(e.what(), Catch::Contains(key));
    }
  };
  refused(R"({"flow": {"time_nodes": 3}})", "time_nodes");
  refused(R"({"planes": {"features": 3}})", "features");
  refused(R"({"time_hash": {"levels": 0}})", "levels");
  refused(R"({"static_hash": {"levls": 4}})", "levls");
  refused(R"({"flw": {}})", "flw");
  refused(R"({"blend": 1})", "blend");
  const auto c = field::Lidar4DEncoderConfig::from_json(
      Json::parse(R"({"blend": false, "flow": {"hidden_width": 32}})"), "lidar4d");
  CHECK_FALSE(c.blend);
  CHECK(c.flow.hidden_width == 32);
  CHECK(c.static_hash.base_resolution == 512.0f);  // LiDAR4D's static hash by default

  auto& rt = test::runtime();
  field::Lidar4DEncoder enc(rt, test::ref::small_lidar4d_config());
  CHECK_THROWS_AS(enc.set_frame(7, 0, 5), Error);
  CHECK_THROWS_AS(enc.set_time(1.5f, 0.1f, true, true), Error);
  CHECK_THROWS_AS(enc.set_level_weights({1.0f}), Error);
  enc.set_frame(4, 0, 5);
  CHECK(enc.time() == 1.0f);
  cl::Buffer b_x(rt, 12 * 10), b_p(rt, enc.n_params() * 4), b_e(rt, 4 * 18 * 10);
  enc.forward(b_p, 0, b_x, 10, b_e);
  CHECK_THROWS_AS(enc.backward(b_p, 0, b_x, 9, b_e, b_p, 0, nullptr), Error);
}
