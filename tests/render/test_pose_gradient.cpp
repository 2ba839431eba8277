// pose_gradient(): dL/d(ω, u) of T = T_init·[Exp(ω)|u] from per-ray dL/do, dL/dd, against
// central differences in double, at ω = 0 and at a large current ω.
#include <catch2/catch.hpp>

#include "render/pose_gradient.hpp"
#include "render_test_data.hpp"

using namespace sgnlf;

namespace {
// A nonlinear loss of world rays: L = Σ_r a_r·o_r + ½|o_r + 2 d_r − q_r|² + b_r·d_r.
struct RayLoss {
  std::vector<double> a, b, q;
  double value(const std::vector<Vec3>& o, const std::vector<Vec3>& d) const {
    double l = 0;
    for (size_t r = 0; r < o.size(); ++r) {
      const Vec3 e = o[r] + 2 * d[r] - Vec3(q[3 * r], q[3 * r + 1], q[3 * r + 2]);
      l += Vec3(a[3 * r], a[3 * r + 1], a[3 * r + 2]).dot(o[r]) + 0.5 * e.squaredNorm() +
           Vec3(b[3 * r], b[3 * r + 1], b[3 * r + 2]).dot(d[r]);
    }
    return l;
  }
};

void world_rays(const Pose& T, const std::vector<float>& p, const std::vector<float>& v,
                std::vector<Vec3>& o, std::vector<Vec3>& d) {
  const size_t n = v.size() / 3;
  o.resize(n);
  d.resize(n);
  for (size_t r = 0; r < n; ++r) {
    const Vec3 pr = p.empty() ? Vec3::Zero() : Vec3(p[3 * r], p[3 * r + 1], p[3 * r + 2]);
    o[r] = T * pr;
    d[r] = T.linear() * Vec3(v[3 * r], v[3 * r + 1], v[3 * r + 2]);
  }
}
}  // namespace

TEST_CASE("Pose gradient matches finite differences in the decoupled parameterisation",
          "[render][pose]") {
  const int n = 50;
  std::vector<float> p, v;
  test::make_rays(n, 21, p, v);
  RayLoss L;
  for (auto* vec : {&L.a, &L.b, &L.q}) {
    const auto f = test::make_uniform(3 * n, -1.f, 1.f, vec == &L.a ? 1 : vec == &L.b ? 2 : 3);
    vec->assign(f.begin(), f.end());
  }
  Pose T_init = Pose::Identity();
  T_init.linear() = exp_so3(Vec3(0.3, -0.7, 1.1));
  T_init.translation() = Vec3(0.2, -0.4, 0.05);

  for (bool with_origins : {false, true})
    for (const Vec6& xi :
         {Vec6::Zero().eval(), (Vec6() << 0.4, -0.9, 0.6, 0.1, -0.2, 0.3).finished()}) {
      const std::vector<float> origins = with_origins ? p : std::vector<float>{};
      std::vector<Vec3> o, d;
      world_rays(sgnlf::corrected_pose(T_init, xi), origins, v, o, d);
      std::vector<float> go(3 * n), gd(3 * n);
      for (int r = 0; r < n; ++r) {
        const Vec3 e = o[r] + 2 * d[r] - Vec3(L.q[3 * r], L.q[3 * r + 1], L.q[3 * r + 2]);
        for (int c = 0; c < 3; ++c) {
          go[3 * r + c] = float(L.a[3 * r + c] + e[c]);
          gd[3 * r + c] = float(2 * e[c] + L.b[3 * r + c]);
        }
      }
      const Vec6 analytic = render::pose_gradient(T_init, xi, origins, v, go, gd);
      Vec6 numeric;
      for (int k = 0; k < 6; ++k) {
        Vec6 xp = xi, xm = xi;
        xp[k] += 1e-6;
        xm[k] -= 1e-6;
        world_rays(sgnlf::corrected_pose(T_init, xp), origins, v, o, d);
        const double lp = L.value(o, d);
        world_rays(sgnlf::corrected_pose(T_init, xm), origins, v, o, d);
        numeric[k] = (lp - L.value(o, d)) / 2e-6;
      }
      INFO("xi " << xi.transpose() << " origins " << with_origins << "\nanalytic "
                 << analytic.transpose() << "\nnumeric  " << numeric.transpose());
      // go, gd are rounded to float: relative 1e-6 of the gradient's size.
      CHECK((analytic - numeric).norm() <= 1e-5 * numeric.norm());
      CHECK(numeric.norm() > 1.0);
    }
}

TEST_CASE("The right Jacobian of SO(3) satisfies Exp(w + e) = Exp(w) Exp(J_r e)",
          "[render][pose]") {
  for (const Vec3& w : {Vec3(0, 0, 0), Vec3(1e-5, 2e-5, -1e-5), Vec3(0.5, -1.2, 2.0)}) {
    const Vec3 e(1e-6, -2e-6, 1.5e-6);
    const Mat3 lhs = exp_so3(w + e);
    const Mat3 rhs = exp_so3(w) * exp_so3(sgnlf::right_jacobian_so3(w) * e);
    CHECK((lhs - rhs).norm() < 1e-11);
  }
}
