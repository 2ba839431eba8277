// The four analytic surfaces: sampling, lattices, charts and their Laplace–Beltrami spectra
// (method.md §4.1 correctness checks). Spectra of −Δ_S, free (Neumann) boundary:
//   sphere radius r:           l(l+1)/r², multiplicity 2l+1;
//   open cylinder R × L:       (m/R)² + (nπ/L)², m, n ≥ 0, multiplicity 2 for m ≥ 1 (cos/sin mφ);
//   square of side a:          π²(m² + n²)/a², m, n ≥ 0;
//   torus of revolution R, r:  no closed form, see torus_spectrum.hpp.
#include <cmath>

#include "core/error.hpp"
#include "spectral/surface.hpp"
#include "spectral/torus_spectrum.hpp"

namespace sgnlf::spectral {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Sorted eigenvalues (with multiplicity) -> the first groups covering n_modes values.
std::vector<SpectrumGroup> first_groups(std::vector<double> values, int n_modes) {
  std::sort(values.begin(), values.end());
  auto groups = group_eigenvalues(values, 1e-9);
  std::vector<SpectrumGroup> out;
  int covered = 0;
  for (const auto& g : groups) {
    if (covered >= n_modes) break;
    out.push_back(g);
    covered += g.multiplicity;
  }
  require(covered >= n_modes, "spectral: analytic spectrum enumeration too short");
  return out;
}

double wrap01(double a) { return a - std::floor(a); }

class Sphere final : public Shape {
 public:
  explicit Sphere(double r) : r_(r) {}
  ShapeKind kind() const override { return ShapeKind::sphere; }
  double area() const override { return 4 * kPi * r_ * r_; }
  SurfacePoint point(const Eigen::Vector3d& n, double w) const {
    SurfacePoint p;
    p.n = n;
    p.x = r_ * n;
    tangent_frame(n, p.t1, p.t2);
    p.w = w;
    return p;
  }
  std::vector<SurfacePoint> sample(Rng& rng, size_t n) const override {
    std::vector<SurfacePoint> pts(n);
    for (auto& p : pts) {  // Archimedes: z uniform in [−1, 1] is area-uniform
      const double z = 2 * rng.uniform_double() - 1, phi = 2 * kPi * rng.uniform_double();
      const double s = std::sqrt(std::max(0.0, 1 - z * z));
      p = point({s * std::cos(phi), s * std::sin(phi), z}, 1.0 / double(n));
    }
    return pts;
  }
  std::vector<SurfacePoint> lattice(size_t n) const override {  // Fibonacci sphere
    std::vector<SurfacePoint> pts(n);
    const double golden = kPi * (3 - std::sqrt(5.0));
    for (size_t i = 0; i < n; ++i) {
      const double z = 1 - (2 * double(i) + 1) / double(n), phi = golden * double(i);
      const double s = std::sqrt(std::max(0.0, 1 - z * z));
      pts[i] = point({s * std::cos(phi), s * std::sin(phi), z}, 1.0 / double(n));
    }
    return pts;
  }
  std::vector<SpectrumGroup> spectrum(int n_modes) const override {
    std::vector<SpectrumGroup> g;
    for (int l = 1, covered = 0; covered < n_modes; covered += 2 * l + 1, ++l)
      g.push_back({l * (l + 1) / (r_ * r_), 2 * l + 1});
    return g;
  }
  Eigen::Vector2d chart(const Eigen::Vector3d& x) const override {
    const Eigen::Vector3d n = x.normalized();
    return {wrap01(std::atan2(n.y(), n.x()) / (2 * kPi)), std::acos(std::clamp(n.z(), -1.0, 1.0)) / kPi};
  }
  SurfacePoint at_chart(double u, double v) const override {
    const double phi = 2 * kPi * u, th = kPi * v;
    return point({std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi), std::cos(th)}, 0);
  }

 private:
  double r_;
};

class Cylinder final : public Shape {
 public:
  Cylinder(double R, double L) : R_(R), L_(L) {}
  ShapeKind kind() const override { return ShapeKind::cylinder; }
  double area() const override { return 2 * kPi * R_ * L_; }
  std::vector<SurfacePoint> sample(Rng& rng, size_t n) const override {
    std::vector<SurfacePoint> pts(n);
    for (auto& p : pts) {
      const double v = rng.uniform_double(), u = rng.uniform_double();  // v first: GCC's order (core/rng.hpp)
      p = at_chart(u, v, 1.0 / double(n));
    }
    return pts;
  }
  std::vector<SurfacePoint> lattice(size_t n) const override {
    const size_t nz = std::max<size_t>(2, size_t(std::sqrt(double(n) * L_ / (2 * kPi * R_))));
    const size_t nphi = std::max<size_t>(2, (n + nz - 1) / nz);  // at least n points
    std::vector<SurfacePoint> pts;
    pts.reserve(nz * nphi);
    for (size_t i = 0; i < nz; ++i)
      for (size_t j = 0; j < nphi; ++j)
        pts.push_back(at_chart((j + 0.5) / nphi, (i + 0.5) / nz, 1.0 / double(nz * nphi)));
    return pts;
  }
  std::vector<SpectrumGroup> spectrum(int n_modes) const override {
    std::vector<double> v;
    for (int m = 0; m <= 4 * n_modes; ++m)
      for (int k = 0; k <= 4 * n_modes; ++k) {
        if (m == 0 && k == 0) continue;
        const double lam = (m / R_) * (m / R_) + (k * kPi / L_) * (k * kPi / L_);
        v.push_back(lam);
        if (m > 0) v.push_back(lam);
      }
    return first_groups(v, n_modes);
  }
  Eigen::Vector2d chart(const Eigen::Vector3d& x) const override {
    return {wrap01(std::atan2(x.y(), x.x()) / (2 * kPi)), x.z() / L_ + 0.5};
  }
  SurfacePoint at_chart(double u, double v) const override { return at_chart(u, v, 0); }

 private:
  SurfacePoint at_chart(double u, double v, double w) const {
    const double phi = 2 * kPi * u;
    SurfacePoint p;
    p.n = {std::cos(phi), std::sin(phi), 0};
    p.x = {R_ * p.n.x(), R_ * p.n.y(), (v - 0.5) * L_};
    p.t1 = {-std::sin(phi), std::cos(phi), 0};
    p.t2 = Eigen::Vector3d::UnitZ();
    p.w = w;
    return p;
  }
  double R_, L_;
};

class Torus final : public Shape {
 public:
  Torus(double R, double r) : R_(R), r_(r) {}
  ShapeKind kind() const override { return ShapeKind::torus; }
  double area() const override { return 4 * kPi * kPi * R_ * r_; }
  std::vector<SurfacePoint> sample(Rng& rng, size_t n) const override {
    std::vector<SurfacePoint> pts(n);
    for (auto& p : pts) {  // dA ∝ (R + r cos θ) dθ dφ: rejection in θ
      double v;
      do v = rng.uniform_double();
      while (rng.uniform_double() * (R_ + r_) > R_ + r_ * std::cos(2 * kPi * v));
      p = at_chart(rng.uniform_double(), v, 1.0 / double(n));
    }
    return pts;
  }
  std::vector<SurfacePoint> lattice(size_t n) const override {
    const size_t nth = std::max<size_t>(4, size_t(std::sqrt(double(n) * r_ / R_)));
    const size_t nphi = std::max<size_t>(4, (n + nth - 1) / nth);  // at least n points
    std::vector<SurfacePoint> pts;
    pts.reserve(nth * nphi);
    double total = 0;
    for (size_t i = 0; i < nth; ++i)
      for (size_t j = 0; j < nphi; ++j) {
        const double v = (i + 0.5) / nth;
        pts.push_back(at_chart((j + 0.5) / nphi, v, R_ + r_ * std::cos(2 * kPi * v)));
        total += pts.back().w;
      }
    for (auto& p : pts) p.w /= total;
    return pts;
  }
  std::vector<SpectrumGroup> spectrum(int n_modes) const override {
    return first_groups(torus_eigenvalues(R_, r_, n_modes + 8), n_modes);
  }
  Eigen::Vector2d chart(const Eigen::Vector3d& x) const override {
    const double rho = std::hypot(x.x(), x.y());
    return {wrap01(std::atan2(x.y(), x.x()) / (2 * kPi)),
            wrap01(std::atan2(x.z(), rho - R_) / (2 * kPi))};
  }
  SurfacePoint at_chart(double u, double v) const override { return at_chart(u, v, 0); }

 private:
  SurfacePoint at_chart(double u, double v, double w) const {
    const double phi = 2 * kPi * u, th = 2 * kPi * v;
    const double rho = R_ + r_ * std::cos(th);
    SurfacePoint p;
    p.x = {rho * std::cos(phi), rho * std::sin(phi), r_ * std::sin(th)};
    p.n = {std::cos(th) * std::cos(phi), std::cos(th) * std::sin(phi), std::sin(th)};
    p.t1 = {-std::sin(phi), std::cos(phi), 0};
    p.t2 = {-std::sin(th) * std::cos(phi), -std::sin(th) * std::sin(phi), std::cos(th)};
    p.w = w;
    return p;
  }
  double R_, r_;
};

class Square final : public Shape {
 public:
  explicit Square(double a) : a_(a) {}
  ShapeKind kind() const override { return ShapeKind::square; }
  double area() const override { return a_ * a_; }
  std::vector<SurfacePoint> sample(Rng& rng, size_t n) const override {
    std::vector<SurfacePoint> pts(n);
    for (auto& p : pts) {
      const double v = rng.uniform_double(), u = rng.uniform_double();  // v first: GCC's order (core/rng.hpp)
      p = at_chart(u, v, 1.0 / double(n));
    }
    return pts;
  }
  std::vector<SurfacePoint> lattice(size_t n) const override {
    const size_t m = std::max<size_t>(2, size_t(std::ceil(std::sqrt(double(n)))));
    std::vector<SurfacePoint> pts;
    pts.reserve(m * m);
    for (size_t i = 0; i < m; ++i)
      for (size_t j = 0; j < m; ++j)
        pts.push_back(at_chart((j + 0.5) / m, (i + 0.5) / m, 1.0 / double(m * m)));
    return pts;
  }
  std::vector<SpectrumGroup> spectrum(int n_modes) const override {
    std::vector<double> v;
    for (int m = 0; m <= 2 * n_modes; ++m)
      for (int k = 0; k <= 2 * n_modes; ++k)
        if (m || k) v.push_back(kPi * kPi * (m * m + k * k) / (a_ * a_));
    return first_groups(v, n_modes);
  }
  Eigen::Vector2d chart(const Eigen::Vector3d& x) const override {
    return {x.x() / a_ + 0.5, x.y() / a_ + 0.5};
  }
  SurfacePoint at_chart(double u, double v) const override { return at_chart(u, v, 0); }

 private:
  SurfacePoint at_chart(double u, double v, double w) const {
    SurfacePoint p;
    p.x = {(u - 0.5) * a_, (v - 0.5) * a_, 0};
    p.w = w;
    return p;  // n = z, t1 = x, t2 = y by default
  }
  double a_;
};

}  // namespace

std::unique_ptr<Shape> make_shape(const ShapeSpec& spec) {
  spec.validate();
  switch (spec.kind) {
    case ShapeKind::sphere: return std::make_unique<Sphere>(spec.radius);
    case ShapeKind::cylinder: return std::make_unique<Cylinder>(spec.radius, spec.length);
    case ShapeKind::torus: return std::make_unique<Torus>(spec.major, spec.radius);
    case ShapeKind::square: return std::make_unique<Square>(spec.side);
  }
  throw ConfigError("spectral: bad shape kind");
}

}  // namespace sgnlf::spectral
