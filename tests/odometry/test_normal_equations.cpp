// The ICP's structured normal equations (odometry/normal_equations.hpp) against the dense
// Σ w JᵀJ and Σ w Jᵀr with J = [−p^, I], on random correspondences (fixed seed), also summed
// in two parts; and the Jacobian itself against finite differences of Exp(δ)·p.
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "odometry/normal_equations.hpp"

using namespace sgnlf;
using namespace sgnlf::odometry;

namespace {

Eigen::Matrix<double, 3, 6> jacobian(const Vec3& p) {
  Eigen::Matrix<double, 3, 6> J;
  J.leftCols<3>() = -hat(p);
  J.rightCols<3>().setIdentity();
  return J;
}

Vec3 random_vec(Rng& rng, double scale) {
  Vec3 v;
  for (int a = 0; a < 3; ++a) v[a] = scale * rng.normal();
  return v;
}

}  // namespace

TEST_CASE("structured normal equations equal the dense sums", "[odometry]") {
  Rng rng(31);
  Eigen::Matrix<double, 6, 6> JTJ = Eigen::Matrix<double, 6, 6>::Zero();
  Vec6 JTr = Vec6::Zero();
  NormalEquations first, second;
  for (int i = 0; i < 500; ++i) {
    const Vec3 p = random_vec(rng, 30.0), r = random_vec(rng, 0.3);
    const double w = 0.1 + rng.uniform_double();
    const auto J = jacobian(p);
    JTJ += w * J.transpose() * J;
    JTr += w * J.transpose() * r;
    (i < 200 ? first : second).add_point(p, r, w);
    (i < 200 ? first : second).count_point(r.squaredNorm());
  }
  NormalEquations n = first;
  n.add(second);
  CHECK(n.count == 500);
  const double scale = JTJ.cwiseAbs().maxCoeff();
  CHECK((n.JTJ() - JTJ).cwiseAbs().maxCoeff() < 1e-12 * scale);
  CHECK((n.JTr - JTr).cwiseAbs().maxCoeff() < 1e-12 * JTr.cwiseAbs().maxCoeff());
}

TEST_CASE("the ICP Jacobian is the derivative of Exp(delta) p", "[odometry]") {
  Rng rng(32);
  const Vec3 p = random_vec(rng, 20.0);
  const double h = 1e-6;
  Eigen::Matrix<double, 3, 6> numeric;
  for (int k = 0; k < 6; ++k) {
    Vec6 d = Vec6::Zero();
    d[k] = h;
    numeric.col(k) = (exp_se3(d) * p - exp_se3(-d) * p) / (2 * h);
  }
  CHECK((numeric - jacobian(p)).cwiseAbs().maxCoeff() < 1e-6);
}
