// Analytic surfaces: frames, area-uniformity of the samplers, lattices, analytic spectra and the
// numerical torus reference.
#include <catch2/catch.hpp>

#include <cmath>

#include "spectral/surface.hpp"
#include "spectral/torus_spectrum.hpp"
#include "spectral/uniformity.hpp"

using namespace sgnlf;
using namespace sgnlf::spectral;

namespace {
const ShapeKind kAll[] = {ShapeKind::sphere, ShapeKind::cylinder, ShapeKind::torus, ShapeKind::square};
}

TEST_CASE("samples carry orthonormal frames and lie on the surface", "[surface]") {
  for (ShapeKind kind : kAll) {
    const auto spec = ShapeSpec::preset(kind);
    const auto shape = make_shape(spec);
    Rng rng(3);
    for (const auto& p : shape->sample(rng, 2000)) {
      REQUIRE(std::fabs(p.n.norm() - 1) < 1e-12);
      REQUIRE(std::fabs(p.t1.norm() - 1) < 1e-12);
      REQUIRE(std::fabs(p.t2.norm() - 1) < 1e-12);
      REQUIRE(std::fabs(p.n.dot(p.t1)) + std::fabs(p.n.dot(p.t2)) + std::fabs(p.t1.dot(p.t2)) < 1e-12);
      const auto uv = shape->chart(p.x);
      REQUIRE((shape->at_chart(uv.x(), uv.y()).x - p.x).norm() < 1e-12);
      REQUIRE(p.x.cwiseAbs().maxCoeff() <= 1.0);
    }
  }
}

TEST_CASE("area-uniform samplers pass a chi-square test on equal-area cells", "[surface]") {
  for (ShapeKind kind : kAll) {
    const auto spec = ShapeSpec::preset(kind);
    const auto shape = make_shape(spec);
    Rng rng(11);
    const auto pts = shape->sample(rng, 200000);
    std::vector<double> prob;
    const auto cells = chart_cells(*shape, spec, pts, 32, 16, prob);
    const auto st = cell_uniformity(cells, prob);
    INFO(to_string(kind) << " chi2/dof " << st.chi2_per_dof << " max rel dev " << st.max_rel_dev);
    // 511 dof: a uniform sample gives 1 ± 0.063; 1.3 is ~5 sigma.
    CHECK(st.chi2_per_dof < 1.3);
    // The test can fail: a sample uniform in the chart instead of in area.
    if (kind == ShapeKind::sphere || kind == ShapeKind::torus) {
      std::vector<SurfacePoint> chart_uniform(pts.size());
      for (auto& p : chart_uniform) p = shape->at_chart(rng.uniform_double(), rng.uniform_double());
      CHECK(cell_uniformity(chart_cells(*shape, spec, chart_uniform, 32, 16, prob), prob).chi2_per_dof > 5);
    }
  }
}

TEST_CASE("lattices have weights summing to one and the right area moments", "[surface]") {
  for (ShapeKind kind : kAll) {
    const auto shape = make_shape(ShapeSpec::preset(kind));
    const auto pts = shape->lattice(40000);
    double wsum = 0;
    Eigen::Vector3d m1 = Eigen::Vector3d::Zero();
    for (const auto& p : pts) {
      wsum += p.w;
      m1 += p.w * p.x;
    }
    CHECK(std::fabs(wsum - 1) < 1e-10);
    CHECK(m1.norm() < 1e-6);  // every shape is centred
  }
}

TEST_CASE("analytic spectra: groups and multiplicities", "[spectrum]") {
  auto sphere = make_shape(ShapeSpec::preset(ShapeKind::sphere))->spectrum(16);
  REQUIRE(sphere.size() == 4);
  for (int l = 1; l <= 4; ++l) {
    CHECK(sphere[l - 1].multiplicity == 2 * l + 1);
    CHECK(sphere[l - 1].value == Approx(l * (l + 1) / 0.64));
  }
  const double c = M_PI * M_PI / (1.6 * 1.6);
  auto square = make_shape(ShapeSpec::preset(ShapeKind::square))->spectrum(16);
  const double sq_vals[] = {1, 2, 4, 5, 8, 9, 10, 13, 16};
  const int sq_mult[] = {2, 1, 2, 2, 1, 2, 2, 2, 2};
  REQUIRE(square.size() == 9);
  for (int i = 0; i < 9; ++i) {
    CHECK(square[i].value == Approx(c * sq_vals[i]));
    CHECK(square[i].multiplicity == sq_mult[i]);
  }
  // Cylinder R 0.4, L 1.6: (m/R)² + (nπ/L)²; m ≥ 1 doubly degenerate.
  auto cyl = make_shape(ShapeSpec::preset(ShapeKind::cylinder))->spectrum(16);
  CHECK(cyl[0].value == Approx(c));
  CHECK(cyl[0].multiplicity == 1);
  CHECK(cyl[1].value == Approx(6.25));
  CHECK(cyl[1].multiplicity == 2);
  CHECK(cyl[2].value == Approx(6.25 + c));
  CHECK(cyl[3].value == Approx(4 * c));
}

TEST_CASE("torus reference: converged in the Fourier order and flat in the thin limit", "[spectrum]") {
  for (int m = 0; m <= 3; ++m) {
    const auto a = torus_order_eigenvalues(0.6, 0.25, m, 32), b = torus_order_eigenvalues(0.6, 0.25, m, 48);
    for (int i = 0; i < 8; ++i) CHECK(std::fabs(a[i] - b[i]) <= 1e-10 * b[i] + 1e-12);
  }
  // R ≫ r: the flat torus (n/r)² + (m/R)² up to O(r/R).
  const double R = 200, r = 1;
  const auto v0 = torus_order_eigenvalues(R, r, 0), v3 = torus_order_eigenvalues(R, r, 3);
  CHECK(std::fabs(v0[0]) < 1e-9);
  CHECK(v0[1] == Approx(1.0).epsilon(1e-2));
  CHECK(v0[3] == Approx(4.0).epsilon(1e-2));
  CHECK(v3[0] == Approx(9 / (R * R)).epsilon(2e-2));
  // m = 0 has no φ term: its lowest non-zero value must be ≥ 1/r² · min ρ / max ρ (Rayleigh).
  const auto t = torus_eigenvalues(0.6, 0.25, 16);
  REQUIRE(t.size() == 16);
  for (size_t i = 1; i < t.size(); ++i) CHECK(t[i] >= t[i - 1]);
  CHECK(t[0] == Approx(t[1]));  // lowest mode is m = 1 (e^{±iφ}): doubly degenerate
}
