// Implicit-surface sampler (Newton projection + |∇f| rejection thinning) and point-set density
// thinning: measured uniformity on equal-area cells of the sphere, and that the tests can fail.
#include <catch2/catch.hpp>

#include <cmath>

#include "spectral/implicit_sampler.hpp"
#include "spectral/point_cloud_surface.hpp"
#include "spectral/uniformity.hpp"

using namespace sgnlf;
using namespace sgnlf::spectral;

namespace {

const ShapeSpec kSphere = ShapeSpec::preset(ShapeKind::sphere);

// f = (|x|² − r²)(1 + 0.6 x): zero set is the sphere, |∇f| on it varies by a factor 4.
ImplicitFunction skewed_sphere() {
  const double r = kSphere.radius;
  ImplicitFunction f;
  f.value = [r](const Eigen::Vector3d& x) { return (x.squaredNorm() - r * r) * (1 + 0.6 * x.x()); };
  f.gradient = [r](const Eigen::Vector3d& x) {
    Eigen::Vector3d g = 2 * x * (1 + 0.6 * x.x());
    g.x() += 0.6 * (x.squaredNorm() - r * r);
    return g;
  };
  return f;
}

UniformityStats sphere_uniformity(const std::vector<SurfacePoint>& pts) {
  const auto shape = make_shape(kSphere);
  std::vector<double> prob;
  return cell_uniformity(chart_cells(*shape, kSphere, pts, 16, 16, prob), prob);
}

}  // namespace

TEST_CASE("implicit sampler: projected points lie on the surface with correct normals", "[sampler]") {
  Rng rng(21);
  ImplicitSamplerConfig cfg;
  ImplicitSamplerStats st;
  auto f = skewed_sphere();
  f.gradient = nullptr;  // finite-difference gradient path
  const auto pts = sample_implicit(f, cfg, 2000, rng, &st);
  REQUIRE(pts.size() == 2000);
  for (const auto& p : pts) {
    REQUIRE(std::fabs(p.x.norm() - kSphere.radius) < 1e-6);
    REQUIRE((p.n - p.x.normalized()).norm() < 1e-6);
    REQUIRE(std::fabs(p.t1.dot(p.n)) + std::fabs(p.t2.dot(p.n)) < 1e-12);
  }
  CHECK(st.accepted == 2000);
  CHECK(st.projected <= st.in_band);
}

TEST_CASE("implicit sampler: rejection thinning makes the density area-uniform", "[sampler]") {
  const size_t n = 40000;  // 256 cells, ~156 per cell
  ImplicitSamplerConfig cfg;
  Rng rng(22);
  const auto thinned = sphere_uniformity(sample_implicit(skewed_sphere(), cfg, n, rng));
  INFO("thinned chi2/dof " << thinned.chi2_per_dof << " max dev " << thinned.max_rel_dev);
  CHECK(thinned.chi2_per_dof < 1.35);  // 255 dof: 1 ± 0.089
  cfg.thin = false;
  Rng rng2(22);
  const auto raw = sphere_uniformity(sample_implicit(skewed_sphere(), cfg, n, rng2));
  INFO("unthinned chi2/dof " << raw.chi2_per_dof);
  CHECK(raw.chi2_per_dof > 5);  // the statistic detects the 1/|∇f| density
}

TEST_CASE("point-set thinning evens out a non-uniform density", "[sampler]") {
  // Points on the sphere with density ∝ 1 + 0.8 z (by rejection from uniform).
  const auto shape = make_shape(kSphere);
  Rng rng(23);
  std::vector<SurfacePoint> skewed;
  while (skewed.size() < 120000) {
    auto p = shape->sample(rng, 1)[0];
    if (rng.uniform_double() * 1.8 < 1 + 0.8 * p.x.z() / kSphere.radius) skewed.push_back(p);
  }
  const auto before = sphere_uniformity(skewed);
  std::vector<Eigen::Vector3d> x;
  for (const auto& p : skewed) x.push_back(p.x);
  const auto keep = thin_to_uniform_density(x, 0.08, rng);
  std::vector<SurfacePoint> kept;
  for (size_t i : keep) kept.push_back(skewed[i]);
  const auto after = sphere_uniformity(kept);
  INFO("before " << before.chi2_per_dof << " after " << after.chi2_per_dof << " kept " << kept.size());
  CHECK(before.chi2_per_dof > 20);
  CHECK(after.chi2_per_dof < 1.35);  // 255 dof: 1 ± 0.089
  CHECK(kept.size() > 10000);
}

TEST_CASE("surface from observed points: uniform thinning and PCA normals", "[sampler]") {
  const auto shape = make_shape(kSphere);
  Rng rng(24);
  std::vector<Eigen::Vector3d> x;
  while (x.size() < 120000) {  // density ∝ 1 + 0.8 z, as a LiDAR scan is denser near the sensor
    const auto p = shape->sample(rng, 1)[0];
    if (rng.uniform_double() * 1.8 < 1 + 0.8 * p.x.z() / kSphere.radius) x.push_back(p.x);
  }
  PointCloudSurfaceStats st;
  const auto pts = surface_from_points(x, 0.08, rng, &st);
  CHECK(st.kept == pts.size());
  CHECK(st.too_few_neighbours == 0);
  double worst = 0;
  for (const auto& p : pts) {
    worst = std::max(worst, 1 - std::fabs(p.n.dot(p.x.normalized())));
    REQUIRE(std::fabs(p.t1.dot(p.n)) + std::fabs(p.t2.dot(p.n)) < 1e-12);
  }
  CHECK(worst < 1e-3);  // |cos| > 0.999: normals within 2.6 degrees
  CHECK(sphere_uniformity(pts).chi2_per_dof < 1.35);
}
