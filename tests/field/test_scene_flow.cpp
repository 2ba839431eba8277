// LiDAR4D's scene-flow field (runtime/field/scene_flow.hpp): config refusals, device vs host
// reference (flow, dL/dparams, dL/dx) and finite differences of the device forward.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "field/scene_flow.hpp"
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
// The small flow field with grid features of order 1 (the ±1e-4 init would hide the grid).
std::vector<float> flow_params(const field::SceneFlow& sf, uint64_t seed) {
  std::vector<float> p(sf.n_params());
  sf.init_params(p, 0, seed);
  const auto g = uniform(sf.mlp_offset(), -1.0f, 1.0f, seed + 9);
  std::copy(g.begin(), g.end(), p.begin());
  return p;
}
}  // namespace

TEST_CASE("scene flow config: LiDAR4D's sizes and refusals naming the key", "[field][flow]") {
  field::SceneFlowConfig c;
  CHECK(c.grid_config().per_level_scale == Approx(std::pow(256.0, 1.0 / 7.0)).epsilon(1e-6));
  CHECK(field::scene_flow_mlp_spec(c).n_in == 16);
  CHECK_FALSE(field::scene_flow_mlp_spec(c).bias);
  auto refused = [](const char* text, const char* key) {
    try {
      field::SceneFlowConfig::from_json(Json::parse(text), "flow");
      FAIL("accepted " << text);
    } catch (const ConfigError& e) {
      CHECK_THAT(e.what(), Catch::Contains(key));
    }
  };
  refused(R"({"time_nodes": 3})", "time_nodes");  // does not divide 8 features
  refused(R"({"features": 6, "time_nodes": 2})", "features");
  refused(R"({"max_resolution": 16})", "max_resolution");  // below base 32
  refused(R"({"levelz": 8})", "levelz");
  refused(R"({"hidden_width": 0})", "hidden_width");
  CHECK(field::SceneFlowConfig::from_json(Json::parse(R"({"time_nodes": 2})"), "flow")
            .time_nodes == 2);
  // The grid's backward, table and schedule reach its HashGridConfig; unwritten at their
  // defaults (the committed configs keep their hashes).
  CHECK(c.grid_config().deterministic);
  CHECK_FALSE(c.to_json().contains("deterministic"));
  CHECK_FALSE(c.to_json().contains("schedule"));
  const auto g = field::SceneFlowConfig::from_json(
                     Json::parse(R"({"deterministic": false, "half_table": true, "schedule": "per_point"})"),
                     "flow")
                     .grid_config();
  CHECK_FALSE(g.deterministic);
  CHECK(g.half_table);
  CHECK(g.schedule == "per_point");
  refused(R"({"schedule": "sideways"})", "schedule");
}

TEST_CASE("scene flow forward and backward match the host reference", "[field][flow]") {
  auto& rt = test::runtime();
  const auto cfg = test::ref::small_lidar4d_config(0.3f).flow;
  field::SceneFlow sf(rt, cfg);
  const int n = 301;
  const auto params = flow_params(sf, 3);
  const auto x = uniform(size_t(n) * 3, -0.9f, 0.9f, 4);
  const auto t = uniform(size_t(n), 0.0f, 1.0f, 5);
  const auto d_flow = uniform(size_t(n) * 6, -1.0f, 1.0f, 6);
  auto b_p = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_t = cl::Buffer::from(rt, t), b_d = cl::Buffer::from(rt, d_flow);
  cl::Buffer b_flow(rt, size_t(n) * 24), b_dx(rt, size_t(n) * 12), b_g(rt, params.size() * 4);
  sf.forward(b_p, 0, b_x, b_t, n, b_flow);
  sf.backward(b_p, 0, b_x, b_t, n, b_flow, b_d, b_g, 0, &b_dx);
  const auto flow = b_flow.read_vec<float>(size_t(n) * 6);
  const auto grad = b_g.read_vec<float>(params.size());
  const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
  const auto flow_ref = test::ref::scene_flow_fwd(cfg, params, x, t);
  std::vector<float> g_ref, dx_ref;
  test::ref::scene_flow_bwd(cfg, params, x, t, d_flow, g_ref, dx_ref);
  double mag = 0;
  for (float v : flow_ref) mag = std::max(mag, double(std::fabs(v)));
  REQUIRE(mag > 0.05);  // the flow is not trivially zero
  CHECK(test::max_abs_err(flow, flow_ref) < 1e-5 * mag);
  CHECK(test::max_sym_rel_err(grad, g_ref, 1e-2) < 1e-4);
  CHECK(test::max_sym_rel_err(dx, dx_ref, 1e-2) < 1e-4);
  // Bias-free: every bias row of the MLP has a zero gradient.
  const auto& spec = sf.mlp().spec();
  for (size_t l = 0; l < spec.layers.size(); ++l) {
    const int in_l = l == 0 ? spec.n_in : spec.layers[l - 1].width;
    const size_t b = sf.mlp_offset() + sf.mlp().layer_offset(int(l)) +
                     size_t(in_l) * size_t(field::Mlp::pad16(spec.layers[l].width));
    for (int o = 0; o < spec.layers[l].width; ++o) CHECK(grad[b + size_t(o)] == 0.0f);
  }
}

TEST_CASE("scene flow gradients agree with finite differences of the device forward",
          "[field][flow][fd]") {
  auto& rt = test::runtime();
  const auto cfg = test::ref::small_lidar4d_config(0.3f).flow;
  field::SceneFlow sf(rt, cfg);
  const int n = 40;
  auto params = flow_params(sf, 7);
  const auto x = uniform(size_t(n) * 3, -0.9f, 0.9f, 8);
  const auto t = uniform(size_t(n), 0.0f, 1.0f, 9);
  const auto r = uniform(size_t(n) * 6, -1.0f, 1.0f, 10);  // L = Σ r · flow
  auto b_p = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_t = cl::Buffer::from(rt, t), b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_flow(rt, size_t(n) * 24), b_dx(rt, size_t(n) * 12), b_g(rt, params.size() * 4);
  sf.forward(b_p, 0, b_x, b_t, n, b_flow);
  sf.backward(b_p, 0, b_x, b_t, n, b_flow, b_r, b_g, 0, &b_dx);
  const auto grad = b_g.read_vec<float>(params.size());
  const auto dx = b_dx.read_vec<float>(size_t(n) * 3);
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& xs) {
    b_p.write_vec(p);
    b_x.write_vec(xs);
    sf.forward(b_p, 0, b_x, b_t, n, b_flow);
    return dot(b_flow.read_vec<float>(size_t(n) * 6), r);
  };
  const float h = 1e-3f;
  std::vector<float> fd, an;
  for (size_t k = 0; k < grad.size() && fd.size() < 80; k += 5) {
    if (grad[k] == 0.0f) continue;
    auto pp = params, pm = params;
    pp[k] += h;
    pm[k] -= h;
    fd.push_back(float((loss(pp, x) - loss(pm, x)) / (2.0 * h)));
    an.push_back(grad[k]);
  }
  REQUIRE(fd.size() >= 40);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 2e-2);
  fd.clear();
  an.clear();
  int agree = 0;
  for (size_t k = 0; k < x.size(); ++k) {
    auto xp = x, xm = x;
    xp[k] += h;
    xm[k] -= h;
    const float f = float((loss(params, xp) - loss(params, xm)) / (2.0 * h));
    agree += test::max_sym_rel_err({f}, {dx[k]}, 1e-1) < 2e-2;
  }
  // Trilinear corners and ReLUs are only piecewise smooth: a step may cross a cell face.
  CHECK(agree >= int(x.size()) * 9 / 10);
}

// The gpu profile's time interpolation (field_scene_flow_time_*_wide: a work-item per output
// word) against the per-point kernels on one device: the same basis weights, products and sum
// order, so within a few ulp (a device may contract them differently; measured bit-equal on
// PoCL); and run to run the same bits. LiDAR4D's 8 levels x 8 features at 4 time nodes and a
// small 2 x 4 at 2, with point counts that leave a work-group part empty.
namespace {
struct FlowShape {
  int levels, features, basis;
};
void check_flow_wide(const std::vector<FlowShape>& shapes, const std::vector<int>& counts) {
  auto& rt = test::runtime();
  for (const FlowShape sh : shapes) {
    for (const int n : counts) {
      CAPTURE(sh.levels, sh.features, sh.basis, n);
      const std::string opt = "-DLEVELS=" + std::to_string(sh.levels) +
                              " -DFEATURES=" + std::to_string(sh.features) +
                              " -DBASIS=" + std::to_string(sh.basis);
      const size_t lf = size_t(sh.levels) * size_t(sh.features), lg = lf / size_t(sh.basis);
      const auto t = uniform(size_t(n), 0.0f, 1.0f, 21);
      const auto in = uniform(size_t(n) * lf, -1.0f, 1.0f, 22);
      const auto d_out = uniform(size_t(n) * lg, -1.0f, 1.0f, 23);
      auto b_t = cl::Buffer::from(rt, t), b_in = cl::Buffer::from(rt, in);
      auto b_dout = cl::Buffer::from(rt, d_out);
      auto run = [&](bool wide) {
        auto fwd = rt.kernel("field/scene_flow.cl",
                             wide ? "field_scene_flow_time_fwd_wide" : "field_scene_flow_time_fwd",
                             opt);
        auto bwd = rt.kernel("field/scene_flow.cl",
                             wide ? "field_scene_flow_time_bwd_wide" : "field_scene_flow_time_bwd",
                             opt);
        auto b_out = cl::Buffer::from(rt, std::vector<float>(size_t(n) * lg, std::nanf("")));
        auto b_din = cl::Buffer::from(rt, std::vector<float>(size_t(n) * lf, std::nanf("")));
        fwd.set_args(n, b_t, b_in, b_out).launch({cl::round_up(size_t(n) * (wide ? lg : 1), 64)}, {64});
        bwd.set_args(n, b_t, b_dout, b_din).launch({cl::round_up(size_t(n) * (wide ? lf : 1), 64)}, {64});
        return std::make_pair(b_out.read_vec<float>(size_t(n) * lg),
                              b_din.read_vec<float>(size_t(n) * lf));
      };
      const auto point = run(false), wide = run(true), again = run(true);
      CHECK(test::same_bits(wide.first, again.first));
      CHECK(test::same_bits(wide.second, again.second));
      // |ℓ_j| ≤ 1.2 on [0, 1] for 4 nodes; terms of order 1: 1e-6 of a floor of 1 is ~8 ulp.
      CHECK(test::sym_rel_err(wide.first, point.first, 1.0) <= 1e-6);
      CHECK(test::sym_rel_err(wide.second, point.second, 1.0) <= 1e-6);
    }
  }
}
}  // namespace

TEST_CASE("scene flow's wide time kernels match the per-point ones", "[field][flow][flow_wide]") {
  check_flow_wide({{8, 8, 4}, {2, 4, 2}}, {1, 37, 301});
}

// LiDAR4D's shape on a few points (oclgrind_field).
TEST_CASE("scene flow's wide time kernels on a small case", "[field][flow][flow_wide][small]") {
  check_flow_wide({{8, 8, 4}}, {37});
}
