// The pose gradient's reduction on the device (render::PoseGradSums, kernels/render/pose_grad.cl;
// device profile pose_grad: device) against its double-precision host reference, run to run,
// and, through render::pose_gradient_from_world_sums, against the host path
// (render::pose_gradient) and central differences of a loss of the world rays.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "render/pose_grad_sums.hpp"
#include "render/pose_gradient.hpp"
#include "render_test_data.hpp"
#include "support/device_tolerance.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;

using namespace sgnlf;

namespace {

// Host reference in double: s_o = Σ g_o, s_x = Σ d × (g_d + g_dir) (g_d + g_dir rounded to float
// first, as the model's read_ray_grads() adds them), and Σ|term| per component, the scale of
// the float sums' rounding.
struct Sums {
  std::vector<double> s = std::vector<double>(6, 0.0), abs = std::vector<double>(6, 0.0);
};
Sums reference(const std::vector<float>& d, const std::vector<float>& go,
               const std::vector<float>& gd, const std::vector<float>& gdir) {
  Sums r;
  for (size_t i = 0; i + 2 < d.size(); i += 3) {
    const Vec3 dv(d[i], d[i + 1], d[i + 2]);
    const Vec3 g(double(gd[i] + gdir[i]), double(gd[i + 1] + gdir[i + 1]),
                 double(gd[i + 2] + gdir[i + 2]));
    const Vec3 x = dv.cross(g);
    for (int c = 0; c < 3; ++c) {
      r.s[size_t(c)] += go[i + size_t(c)], r.abs[size_t(c)] += std::abs(go[i + size_t(c)]);
      r.s[size_t(3 + c)] += x[c], r.abs[size_t(3 + c)] += std::abs(x[c]);
    }
  }
  return r;
}

std::vector<float> device_sums(render::PoseGradSums& sums, cl::Runtime& rt,
                               const std::vector<float>& d, const std::vector<float>& go,
                               const std::vector<float>& gd, const std::vector<float>& gdir) {
  const int n = int(d.size() / 3);
  auto bd = cl::Buffer::from(rt, d), bo = cl::Buffer::from(rt, go), bg = cl::Buffer::from(rt, gd),
       bdir = cl::Buffer::from(rt, gdir);
  sums.reduce(n, bd, bo, bg, bdir);
  return sums.sums().read_vec<float>(6);
}

}  // namespace

TEST_CASE("Pose gradient sums on the device equal the double reference",
          "[render][pose][pose_grad_sums][device]") {
  auto& rt = test::runtime();
  render::PoseGradSums sums(rt);
  // Fewer rays than work-items, one per work-item, strided tails, the audit's 4096, more.
  for (const int n : {1, 5, 255, 256, 257, 1000, 4096, 5003}) {
    CAPTURE(n);
    std::vector<float> o, d;
    test::make_rays(n, uint64_t(100 + n), o, d);
    const auto go = test::make_uniform(size_t(n) * 3, -1.f, 1.f, uint64_t(3 * n + 1));
    const auto gd = test::make_uniform(size_t(n) * 3, -2.f, 2.f, uint64_t(3 * n + 2));
    const auto gdir = test::make_uniform(size_t(n) * 3, -0.5f, 0.5f, uint64_t(3 * n + 3));
    const Sums ref = reference(d, go, gd, gdir);
    const auto dev = device_sums(sums, rt, d, go, gd, gdir);
    // Float sums of n terms in strided partials and a tree: their rounding scales with Σ|term|,
    // not with the (cancelling) sum, so each component's floor is its Σ|term|: an error of
    // (n / 256 + 8) float roundings of it at most, 2e-6 at these sizes; 1e-5 allows for the
    // cross products' rounding (contracted into fma or not) on any device.
    for (int k = 0; k < 6; ++k) {
      CAPTURE(k);
      CHECK(test::sym_rel_err({dev[size_t(k)]}, {float(ref.s[size_t(k)])}, ref.abs[size_t(k)]) <=
            1e-5);
    }
    // A fixed tree: the same bits on a second run of the same device.
    const auto again = device_sums(sums, rt, d, go, gd, gdir);
    CHECK(std::memcmp(again.data(), dev.data(), 6 * sizeof(float)) == 0);
    // read() gives the same six numbers.
    const render::RayGradSums r = sums.read();
    CHECK(float(r.origin[0]) == dev[0]);
    CHECK(float(r.cross[2]) == dev[5]);
  }
  auto small = cl::Buffer::from(rt, std::vector<float>(6, 0.0f));
  CHECK_THROWS_AS(sums.reduce(3, small, small, small, small), Error);  // 9 floats needed
}

TEST_CASE("The pose gradient from the device sums equals the host path and finite differences",
          "[render][pose][pose_grad_sums][device]") {
  auto& rt = test::runtime();
  render::PoseGradSums sums(rt);
  const int n = 700;
  std::vector<float> p_unused, v;
  test::make_rays(n, 37, p_unused, v);  // unit directions in the LiDAR frame
  // L = Σ_r a_r·o_r + ½|o_r + 2 d_r − q_r|² + b_r·d_r over rays from the sensor origin.
  const auto a = test::make_uniform(size_t(n) * 3, -1.f, 1.f, 41);
  const auto b = test::make_uniform(size_t(n) * 3, -1.f, 1.f, 42);
  const auto q = test::make_uniform(size_t(n) * 3, -1.f, 1.f, 43);
  auto loss = [&](const Pose& T) {
    double l = 0;
    for (int r = 0; r < n; ++r) {
      const Vec3 o = T.translation();
      const Vec3 d = T.linear() * Vec3(v[3 * r], v[3 * r + 1], v[3 * r + 2]);
      const Vec3 A(a[3 * r], a[3 * r + 1], a[3 * r + 2]), B(b[3 * r], b[3 * r + 1], b[3 * r + 2]);
      const Vec3 e = o + 2 * d - Vec3(q[3 * r], q[3 * r + 1], q[3 * r + 2]);
      l += A.dot(o) + 0.5 * e.squaredNorm() + B.dot(d);
    }
    return l;
  };
  Pose T_init = Pose::Identity();
  T_init.linear() = exp_so3(Vec3(0.3, -0.7, 1.1));
  T_init.translation() = Vec3(0.2, -0.4, 0.05);
  for (const Vec6& xi : {Vec6::Zero().eval(), (Vec6() << 0.4, -0.9, 0.6, 0.1, -0.2, 0.3).finished()}) {
    const Pose T = corrected_pose(T_init, xi);
    // The rays as the model holds them (world directions in float) and their gradients.
    std::vector<float> d(size_t(n) * 3), go(size_t(n) * 3), gd(size_t(n) * 3),
        gdir(size_t(n) * 3, 0.0f);
    for (int r = 0; r < n; ++r) {
      const Vec3 dw = T.linear() * Vec3(v[3 * r], v[3 * r + 1], v[3 * r + 2]);
      const Vec3 e = T.translation() + 2 * dw - Vec3(q[3 * r], q[3 * r + 1], q[3 * r + 2]);
      for (int c = 0; c < 3; ++c) {
        d[3 * r + c] = float(dw[c]);
        go[3 * r + c] = float(a[3 * r + c] + e[c]);
        // Split dL/dd between the renderer's share and the direction encoding's.
        const double g = 2 * e[c] + b[3 * r + c];
        gdir[3 * r + c] = float(0.25 * g);
        gd[3 * r + c] = float(g - double(gdir[3 * r + c]));
      }
    }
    device_sums(sums, rt, d, go, gd, gdir);
    const render::RayGradSums s = sums.read();
    const Vec6 dev = render::pose_gradient_from_world_sums(T_init, xi, s.origin, s.cross);
    std::vector<float> gsum(gd.size());
    for (size_t i = 0; i < gd.size(); ++i) gsum[i] = gd[i] + gdir[i];
    const Vec6 host = render::pose_gradient(T_init, xi, {}, v, go, gsum);
    Vec6 numeric;
    for (int k = 0; k < 6; ++k) {
      Vec6 xp = xi, xm = xi;
      xp[k] += 1e-6;
      xm[k] -= 1e-6;
      numeric[k] = (loss(corrected_pose(T_init, xp)) - loss(corrected_pose(T_init, xm))) / 2e-6;
    }
    INFO("xi " << xi.transpose() << "\ndevice  " << dev.transpose() << "\nhost    "
               << host.transpose() << "\nnumeric " << numeric.transpose());
    // The gradients are rounded to float (relative 1e-6 of the gradient's size, as in the host
    // path's test), the device's sums and world directions add float rounding of the same order.
    CHECK((dev - numeric).norm() <= 1e-5 * numeric.norm());
    CHECK((dev - host).norm() <= 1e-5 * host.norm());
    CHECK(numeric.norm() > 1.0);
  }
}
