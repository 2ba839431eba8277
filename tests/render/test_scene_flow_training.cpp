// The scene-flow field (field/scene_flow.hpp) trained with the flow loss
// (render/scene_flow_loss.hpp) on a synthetic sequence: a static point set and an object moving
// at a constant velocity. The field has to learn the object's displacement and keep the static
// points still; the loss must fall well below the zero-flow loss.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/rng.hpp"
#include "field/adam.hpp"
#include "field/frame_time.hpp"
#include "field/scene_flow.hpp"
#include "render/scene_flow_loss.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using render::Point3f;

TEST_CASE("a scene-flow field trained with the flow loss learns a moving object's displacement",
          "[render][flow][train]") {
  auto& rt = test::runtime();
  const int frames = 5, n_static = 240, n_obj = 160;
  const Point3f v(0.04f, 0.015f, 0.0f);  // object displacement per frame (normalised box)
  Rng rng(3);
  std::vector<Point3f> base;
  // One draw per statement: the order of a call's arguments is unspecified (core/rng.hpp).
  auto draw = [&](const Point3f& lo, const Point3f& hi) {
    Point3f p;
    for (int k = 0; k < 3; ++k) p[k] = rng.uniform(lo[k], hi[k]);
    base.push_back(p);
  };
  for (int i = 0; i < n_static; ++i)  // static: a slab on the left
    draw(Point3f(-0.8f, -0.6f, -0.3f), Point3f(-0.2f, 0.6f, 0.3f));
  for (int i = 0; i < n_obj; ++i)  // object: a box on the right, moving
    draw(Point3f(0.1f, -0.2f, -0.15f), Point3f(0.35f, 0.1f, 0.15f));
  std::vector<std::vector<Point3f>> seq(frames, base);
  for (int k = 0; k < frames; ++k)
    for (int i = n_static; i < n_static + n_obj; ++i) seq[size_t(k)][size_t(i)] += float(k) * v;

  field::SceneFlowConfig cfg;
  cfg.levels = 4;
  cfg.features = 4;
  cfg.time_nodes = 2;
  cfg.base_resolution = 4.0f;
  cfg.max_resolution = 32.0f;
  cfg.log2_table_size = 12;
  cfg.hidden_width = 32;
  cfg.hidden_layers = 2;
  field::SceneFlow sf(rt, cfg);
  std::vector<float> params(sf.n_params());
  sf.init_params(params, 0, 11);
  auto b_p = cl::Buffer::from(rt, params);
  cl::Buffer b_g(rt, params.size() * 4);
  const int n = n_static + n_obj;
  cl::Buffer b_x(rt, size_t(n) * 12), b_t(rt, size_t(n) * 4), b_flow(rt, size_t(n) * 24),
      b_d(rt, size_t(n) * 24);
  field::Adam adam(rt, params.size());

  auto neighbours = [&](int k) {
    render::FlowNeighbours nb;
    for (int s = 1; s <= 2; ++s) {
      if (k + s < frames) nb.next[s - 1] = &seq[size_t(k + s)];
      if (k - s >= 0) nb.prev[s - 1] = &seq[size_t(k - s)];
    }
    return nb;
  };
  auto run = [&](int k, bool train) {
    std::vector<float> x, t(size_t(n), field::frame_time(k, 0, frames));
    for (const auto& p : seq[size_t(k)]) x.insert(x.end(), {p.x(), p.y(), p.z()});
    b_x.write_vec(x);
    b_t.write_vec(t);
    sf.forward(b_p, 0, b_x, b_t, n, b_flow);
    const auto flow = b_flow.read_vec<float>(size_t(n) * 6);
    const auto l = render::scene_flow_loss(seq[size_t(k)], flow, neighbours(k));
    if (train) {
      b_d.write_vec(l.d_flow);
      sf.backward(b_p, 0, b_x, b_t, n, b_flow, b_d, b_g, 0);
      adam.begin_step();
      adam.update(b_p, b_g, 0, sf.mlp_offset(), 1e-2f);  // encoders' lr (method.md §0)
      adam.update(b_p, b_g, sf.mlp_offset(), sf.n_params() - sf.mlp_offset(), 1e-3f);  // MLPs
    }
    return std::make_pair(l.loss, flow);
  };
  double zero_flow = 0;
  for (int k = 0; k < frames; ++k) {
    const std::vector<float> z(size_t(n) * 6, 0.0f);
    zero_flow += render::scene_flow_loss(seq[size_t(k)], z, neighbours(k)).loss;
  }
  double initial = 0;
  for (int k = 0; k < frames; ++k) initial += run(k, false).first;
  for (int step = 0; step < 400; ++step) run(step % frames, true);
  double final_loss = 0;
  double obj_err = 0, static_mag = 0;
  for (int k = 0; k < frames; ++k) {
    const auto [l, flow] = run(k, false);
    final_loss += l;
    if (k == 0 || k == frames - 1) continue;
    for (int i = 0; i < n; ++i) {
      const Point3f fwd(flow[6 * i], flow[6 * i + 1], flow[6 * i + 2]);
      const Point3f bwd(flow[6 * i + 3], flow[6 * i + 4], flow[6 * i + 5]);
      if (i >= n_static)
        obj_err += double((fwd - v).norm() + (bwd + v).norm()) / (2.0 * n_obj * (frames - 2));
      else
        static_mag += double(fwd.norm() + bwd.norm()) / (2.0 * n_static * (frames - 2));
    }
  }
  INFO("zero-flow " << zero_flow << ", initial " << initial << ", final " << final_loss
                    << ", object error " << obj_err << ", static flow " << static_mag);
  CHECK(initial == Approx(zero_flow).epsilon(0.2));  // the flow starts near zero
  CHECK(final_loss < 0.05 * zero_flow);  // measured 0.015 of 3.89
  CHECK(obj_err < 0.1 * double(v.norm()));  // measured 0.0013 of 0.043
  CHECK(static_mag < 0.1 * double(v.norm()));
}
