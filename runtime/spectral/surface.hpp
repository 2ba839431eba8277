// Analytic test surfaces for the spectral embedding (method.md §4.1 correctness checks): sphere,
// open cylinder, torus of revolution and flat square. Each gives area-uniform random samples and a
// quasi-uniform lattice, every point with its unit normal, two unit tangents and a weight
// (weights of a set sum to 1 and stand for dA / A).
#pragma once
#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "core/rng.hpp"

namespace sgnlf::spectral {

struct SurfacePoint {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();   // unit normal
  Eigen::Vector3d t1 = Eigen::Vector3d::UnitX();  // unit tangents, t1 ⟂ t2 ⟂ n
  Eigen::Vector3d t2 = Eigen::Vector3d::UnitY();
  double w = 1.0;  // quadrature weight (a set's weights sum to 1)
};

// Two unit tangents completing a unit normal to a right-handed frame (t1, t2, n).
void tangent_frame(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2);

enum class ShapeKind { sphere, cylinder, torus, square };
ShapeKind shape_kind_from_string(const std::string& name);
std::string to_string(ShapeKind kind);

// Dimensions in unit-box coordinates; the defaults fit in [−1, 1]³.
struct ShapeSpec {
  ShapeKind kind = ShapeKind::sphere;
  double radius = 0.8;  // sphere radius, cylinder radius, torus tube (minor) radius
  double major = 0.6;   // torus: distance from the axis to the tube centre
  double length = 1.6;  // cylinder length (axis z, centred)
  double side = 1.6;    // square side (plane z = 0, centred)
  // Defaults for a kind: sphere r 0.8; cylinder R 0.4, L 1.6; torus R 0.6, r 0.25; square a 1.6.
  static ShapeSpec preset(ShapeKind kind);
  void validate() const;
};

// One eigenvalue of −Δ_S with its multiplicity.
struct SpectrumGroup {
  double value = 0;
  int multiplicity = 1;
};

class Shape {
 public:
  virtual ~Shape() = default;
  virtual ShapeKind kind() const = 0;
  virtual double area() const = 0;
  // n area-uniform random points (weights 1/n).
  virtual std::vector<SurfacePoint> sample(Rng& rng, size_t n) const = 0;
  // A quasi-uniform lattice of at least n_target points (a few more) with area weights.
  virtual std::vector<SurfacePoint> lattice(size_t n_target) const = 0;
  // The smallest non-zero eigenvalue groups of −Δ_S (free/Neumann boundary where there is
  // one), ascending, until at least n_modes eigenvalues are covered.
  virtual std::vector<SpectrumGroup> spectrum(int n_modes) const = 0;
  // Surface parameters (u, v) ∈ [0, 1]² of a surface point, for pictures.
  virtual Eigen::Vector2d chart(const Eigen::Vector3d& x) const = 0;
  // The surface point at chart coordinates (u, v) ∈ [0, 1]².
  virtual SurfacePoint at_chart(double u, double v) const = 0;
};

std::unique_ptr<Shape> make_shape(const ShapeSpec& spec);

// Groups a sorted list of eigenvalues whose relative gaps are below rel_tol.
std::vector<SpectrumGroup> group_eigenvalues(const std::vector<double>& sorted, double rel_tol);

}  // namespace sgnlf::spectral
