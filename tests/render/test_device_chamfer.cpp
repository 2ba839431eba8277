// LiDAR4D's Chamfer losses on the device (render::DeviceChamfer, DeviceSceneFlowLoss;
// kernels/render/chamfer.cl; device profile chamfer: device) against the host's
// render::chamfer_loss, ray_chamfer_loss, scene_flow_loss and ground_flow_penalty (their
// reference: the k-d tree's exact neighbours, sums in double), with exact ties, empty and
// missing sets and masked rays; the gradient against central differences of the device's own
// loss; the same bits on a second run.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/rng.hpp"
#include "render/chamfer_loss.hpp"
#include "render/device_chamfer.hpp"
#include "render/device_scene_flow_loss.hpp"
#include "render/scene_flow_loss.hpp"
#include "render_test_data.hpp"
#include "support/device_tolerance.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;

using namespace sgnlf;
using render::Point3f;

namespace {

std::vector<Point3f> cloud(size_t n, float lo, float hi, uint64_t seed) {
  Rng r(seed, 21);
  std::vector<Point3f> p(n);
  for (auto& q : p) {
    const float a = r.uniform(lo, hi), b = r.uniform(lo, hi), c = r.uniform(lo, hi);
    q = Point3f(a, b, c);
  }
  return p;
}
// Integer points on a small grid: many exactly equal distances (ties) and duplicate points.
std::vector<Point3f> grid_cloud(size_t n, int side, uint64_t seed) {
  Rng r(seed, 22);
  std::vector<Point3f> p(n);
  for (auto& q : p)
    for (int k = 0; k < 3; ++k) q[k] = float(int(r.uniform(0.0f, float(side))));
  return p;
}
std::vector<float> flat(const std::vector<Point3f>& p) {
  std::vector<float> v;
  for (const auto& q : p) v.insert(v.end(), {q.x(), q.y(), q.z()});
  return v;
}
cl::Buffer upload(const std::vector<float>& v) { return cl::Buffer::from(test::runtime(), v); }
// The floor of a comparison: rel of the largest magnitude (values near 0 are compared in
// absolute terms against it).
double floor_of(const std::vector<float>& v, double rel) {
  double m = 0;
  for (float x : v) m = std::max(m, double(std::abs(x)));
  return std::max(m * rel, 1e-30);
}

struct DeviceResult {
  double loss = 0;
  std::vector<float> grad;
};
DeviceResult device_chamfer(render::DeviceChamfer& dc, const std::vector<Point3f>& pred,
                            const std::vector<Point3f>& target, render::ChamferReduce reduce) {
  cl::Buffer p = upload(flat(pred)), t = upload(flat(target));
  cl::Buffer g(test::runtime(), std::max<size_t>(1, pred.size()) * 3 * sizeof(float));
  cl::Buffer loss(test::runtime(), 2 * sizeof(float));
  render::ChamferGradOut out;
  out.out = &g;
  dc.run(p, int(pred.size()), t, int(target.size()), reduce, 1.0f, out, loss, 1);
  return {double(loss.read_vec<float>(1, 1)[0]), g.read_vec<float>(pred.size() * 3)};
}
std::vector<float> host_grad(const render::ChamferLoss& c) {
  std::vector<float> g;
  for (const auto& q : c.d_pred) g.insert(g.end(), {q.x(), q.y(), q.z()});
  return g;
}

void check_against_host(render::DeviceChamfer& dc, const std::vector<Point3f>& pred,
                        const std::vector<Point3f>& target) {
  for (auto reduce : {render::ChamferReduce::Mean, render::ChamferReduce::Sum}) {
    CAPTURE(pred.size(), target.size(), int(reduce));
    const auto host = render::chamfer_loss(pred, target, reduce);
    const auto dev = device_chamfer(dc, pred, target, reduce);
    // The same neighbours (IEEE distances, ties to the lowest index) and the gradient's float
    // operations in the host's order: the gradient differs by contraction at most. The loss:
    // a float tree against the host's double sum, within (n / 256 + 8) roundings of the sum
    // of positive terms.
    CHECK(test::sym_rel_err({float(dev.loss)}, {float(host.loss)}, 1e-12) <= 1e-5);
    const auto hg = host_grad(host);
    CHECK(test::sym_rel_err(dev.grad, hg, floor_of(hg, 1e-6)) <= 1e-5);
  }
}

// The flow supervision's host value and gradient as FlowSupervisionStep combines them.
struct HostFlow {
  double loss = 0;
  std::vector<float> d_flow;
};
HostFlow host_flow(const std::vector<Point3f>& moving, const std::vector<float>& flow,
                   const render::FlowNeighbours& nb, int steps, double w, float gw) {
  const size_t m = moving.size();
  const std::vector<float> fm(flow.begin(), flow.begin() + long(m) * 6);
  const std::vector<float> fg(flow.begin() + long(m) * 6, flow.end());
  const auto lm = render::scene_flow_loss(moving, fm, nb, steps);
  const auto lg = render::ground_flow_penalty(fg, gw);
  HostFlow h;
  h.d_flow.resize(flow.size());
  for (size_t i = 0; i < m * 6; ++i) h.d_flow[i] = float(w * lm.d_flow[i]);
  for (size_t i = 0; i < fg.size(); ++i) h.d_flow[m * 6 + i] = lg.d_flow[i];
  h.loss = w * lm.loss + lg.loss;
  return h;
}

// One flow case: m moving + g ground points, neighbours k+1 (present), k−1 (missing: null),
// k+2 (empty), k−2 (present); steps 1 and 2.
void check_flow(size_t m, size_t g, size_t nt) {
  auto& rt = test::runtime();
  render::DeviceSceneFlowLoss dev(rt);
  const auto moving = cloud(m, -1.0f, 1.0f, 31), ground = cloud(g, -1.0f, 1.0f, 32);
  const auto next1 = cloud(nt, -1.0f, 1.0f, 33), prev2 = cloud(nt + 7, -1.0f, 1.0f, 34);
  const std::vector<Point3f> none;
  auto flow = test::make_uniform((m + g) * 6, -0.1f, 0.1f, 35);
  if (g > 0) flow[m * 6 + 1] = 0.0f;  // the penalty's gradient at 0 is 0
  std::vector<Point3f> all = moving;
  all.insert(all.end(), ground.begin(), ground.end());
  cl::Buffer x = upload(flat(all)), f = upload(flow), bn1 = upload(flat(next1)),
             bp2 = upload(flat(prev2)), bnone(rt, sizeof(float));
  cl::Buffer d_flow(rt, (m + g) * 6 * sizeof(float));
  const double w = 0.01;
  const float gw = 0.001f;
  for (int steps : {1, 2}) {
    CAPTURE(m, g, nt, steps);
    render::FlowNeighbours nb;
    nb.next[0] = &next1, nb.prev[0] = nullptr, nb.next[1] = &none, nb.prev[1] = &prev2;
    render::DeviceFlowNeighbours dnb;
    dnb.next[0] = &bn1, dnb.n_next[0] = int(nt);
    dnb.next[1] = &bnone, dnb.n_next[1] = 0;
    dnb.prev[1] = &bp2, dnb.n_prev[1] = int(nt + 7);
    const HostFlow h = host_flow(moving, flow, nb, steps, w, gw);
    dev.run(x, int(m), int(g), f, dnb, steps, float(w), gw, d_flow);
    const auto dg = d_flow.read_vec<float>((m + g) * 6);
    const double dl = dev.read(w);
    CHECK(test::sym_rel_err({float(dl)}, {float(h.loss)}, 1e-12) <= 1e-5);
    CHECK(test::sym_rel_err(dg, h.d_flow, floor_of(h.d_flow, 1e-6)) <= 1e-5);
    // A second run: the same bits (fixed sums, no atomics).
    dev.run(x, int(m), int(g), f, dnb, steps, float(w), gw, d_flow);
    CHECK(test::same_bits(d_flow.read_vec<float>((m + g) * 6), dg));
    CHECK(dev.read(w) == dl);
  }
}

// The ray term: n rays, a third without a return (label 0), on an output gradient that
// already holds the range loss's values.
void check_rays(int n) {
  auto& rt = test::runtime();
  render::DeviceChamfer dc(rt);
  std::vector<float> o, dir;
  test::make_rays(n, uint64_t(40 + n), o, dir);
  const auto depth_raw = test::make_uniform(size_t(n), 0.05f, 1.0f, 41);
  const auto range_raw = test::make_uniform(size_t(n), 0.05f, 1.0f, 42);
  const auto grad0 = test::make_uniform(size_t(n) * 3, -1.0f, 1.0f, 43);
  std::vector<float> out(size_t(n) * 3, 0.5f), target(size_t(n) * 3, 0.25f);
  const size_t un = static_cast<size_t>(n);
  std::vector<float> depth(un), gt(un), label(un);
  for (size_t i = 0; i < size_t(n); ++i) {
    label[i] = i % 3 == 1 ? 0.0f : 1.0f;
    out[3 * i] = depth_raw[i], target[3 * i] = range_raw[i], target[3 * i + 2] = label[i];
    depth[i] = depth_raw[i] * label[i], gt[i] = range_raw[i] * label[i];
  }
  const float scale = 0.7f, weight = 2.0f;
  const auto host = render::ray_chamfer_loss(dir, depth, gt, scale, weight);
  std::vector<float> expect = grad0;
  for (size_t i = 0; i < size_t(n); ++i)
    if (label[i] > 0.5f) expect[3 * i] += host.d_depth[i];
  cl::Buffer bd = upload(dir), bo = upload(out), bt = upload(target), bg = upload(grad0);
  cl::Buffer loss(rt, 3 * sizeof(float));
  dc.ray(bd, bo, bt, n, scale, weight, bg, loss, 2);
  const auto g = bg.read_vec<float>(size_t(n) * 3);
  const float l = loss.read_vec<float>(1, 2)[0];
  CAPTURE(n);
  CHECK(test::sym_rel_err({l}, {float(host.loss)}, 1e-12) <= 1e-5);
  // Only the depth column of rays with a return moves; the added d_depth against the host's.
  std::vector<float> dd(un), hd(un);
  size_t other = 0;
  for (size_t i = 0; i < size_t(n); ++i) {
    dd[i] = g[3 * i] - grad0[3 * i], hd[i] = expect[3 * i] - grad0[3 * i];
    other += g[3 * i + 1] != grad0[3 * i + 1] || g[3 * i + 2] != grad0[3 * i + 2] ||
             (label[i] <= 0.5f && g[3 * i] != grad0[3 * i]);
  }
  CHECK(other == 0);
  // The difference of two floats near grad0 (|grad0| <= 1) carries grad0's rounding: the floor
  // is an ulp of it.
  CHECK(test::sym_rel_err(dd, hd, std::max(floor_of(hd, 1e-5), 1e-6)) <= 1e-4);
}

}  // namespace

TEST_CASE("Device Chamfer on small sets equals the host's with ties and empty sets",
          "[render][chamfer_device][small][device]") {
  auto& rt = test::runtime();
  render::DeviceChamfer dc(rt);
  // One point, fewer than a tile, tiles with tails.
  check_against_host(dc, cloud(1, -1, 1, 1), cloud(1, -1, 1, 2));
  check_against_host(dc, cloud(5, -1, 1, 3), cloud(70, -1, 1, 4));
  check_against_host(dc, cloud(130, -1, 1, 5), cloud(9, -1, 1, 6));
  // Exact ties and duplicates: integer grid points, the target holding the pred's points twice.
  {
    const auto pred = grid_cloud(90, 3, 7);
    auto target = grid_cloud(60, 3, 8);
    target.insert(target.end(), pred.begin(), pred.begin() + 20);
    target.insert(target.end(), pred.begin(), pred.begin() + 20);
    check_against_host(dc, pred, target);
  }
  // Empty sets: a zero loss and gradient (written over what was there, or nothing added).
  {
    cl::Buffer p = upload(flat(cloud(4, -1, 1, 9))), g = upload(std::vector<float>(12, 7.0f));
    cl::Buffer loss = upload({5.0f});
    render::ChamferGradOut out;
    out.out = &g;
    dc.run(p, 4, p, 0, render::ChamferReduce::Mean, 1.0f, out, loss, 0);
    CHECK(g.read_vec<float>(12) == std::vector<float>(12, 0.0f));
    CHECK(loss.read_vec<float>(1)[0] == 0.0f);
    g.write_vec(std::vector<float>(12, 7.0f));
    out.accumulate = true;
    dc.run(p, 4, p, 0, render::ChamferReduce::Sum, 1.0f, out, loss, 0);
    CHECK(g.read_vec<float>(12) == std::vector<float>(12, 7.0f));
    dc.run(p, 0, p, 4, render::ChamferReduce::Sum, 1.0f, out, loss, 0);
    CHECK(loss.read_vec<float>(1)[0] == 0.0f);
  }
  check_rays(70);
  check_flow(40, 9, 50);
  check_flow(0, 5, 20);  // no moving points: the ground penalty alone
}

TEST_CASE("Device Chamfer at the batch's sizes equals the host's", "[render][chamfer_device][device]") {
  auto& rt = test::runtime();
  render::DeviceChamfer dc(rt);
  check_against_host(dc, cloud(4096, -1, 1, 11), cloud(4096, -1, 1, 12));
  check_against_host(dc, cloud(1000, -1, 1, 13), cloud(2500, -1, 1, 14));
  check_rays(4096);
  check_flow(2048, 256, 2100);
}

TEST_CASE("Device Chamfer gradient equals central differences of its loss",
          "[render][chamfer_device][fd][device]") {
  auto& rt = test::runtime();
  render::DeviceChamfer dc(rt);
  // Points well apart, so that a step of h changes no neighbour.
  const auto pred = cloud(40, -2, 2, 51), target = cloud(55, -2, 2, 52);
  for (auto reduce : {render::ChamferReduce::Mean, render::ChamferReduce::Sum}) {
    CAPTURE(int(reduce));
    const auto base = device_chamfer(dc, pred, target, reduce);
    const double h = 1e-3;
    // The loss in float: its rounding (an ulp of L, ~4e-7 · L) over 2h bounds the error.
    const double noise = 1e-6 * std::max(1.0, base.loss) / h;
    int checked = 0;
    for (size_t i = 0; i < pred.size(); i += 3)
      for (int k = 0; k < 3; ++k) {
        auto p = pred, m = pred;
        p[i][k] += float(h), m[i][k] -= float(h);
        const double fd = (device_chamfer(dc, p, target, reduce).loss -
                           device_chamfer(dc, m, target, reduce).loss) /
                          (double(p[i][k]) - double(m[i][k]));
        CHECK(fd == Approx(base.grad[3 * i + size_t(k)]).margin(noise + 1e-4).epsilon(1e-2));
        ++checked;
      }
    CHECK(checked >= 40);
  }
}
