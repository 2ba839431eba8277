// Shared pieces of the analytic surfaces: tangent frames, shape names, presets, grouping.
#include "spectral/surface.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "core/error.hpp"

namespace sgnlf::spectral {

void tangent_frame(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  // Cross with the axis least aligned with n: well conditioned for every n.
  const Eigen::Vector3d a = std::fabs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX()
                            : std::fabs(n.y()) < 0.6 ? Eigen::Vector3d::UnitY()
                                                     : Eigen::Vector3d::UnitZ();
  t1 = a.cross(n).normalized();
  t2 = n.cross(t1);
}

ShapeKind shape_kind_from_string(const std::string& name) {
  if (name == "sphere") return ShapeKind::sphere;
  if (name == "cylinder") return ShapeKind::cylinder;
  if (name == "torus") return ShapeKind::torus;
  if (name == "square") return ShapeKind::square;
  throw ConfigError("spectral: unknown shape '" + name + "' (sphere, cylinder, torus, square)");
}

std::string to_string(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::sphere: return "sphere";
    case ShapeKind::cylinder: return "cylinder";
    case ShapeKind::torus: return "torus";
    case ShapeKind::square: return "square";
  }
  return "?";
}

ShapeSpec ShapeSpec::preset(ShapeKind kind) {
  ShapeSpec s;
  s.kind = kind;
  if (kind == ShapeKind::cylinder) s.radius = 0.4;
  if (kind == ShapeKind::torus) s.radius = 0.25;
  return s;
}

void ShapeSpec::validate() const {
  const std::string w = "spectral shape " + to_string(kind);
  check_range(w, "radius", radius, 1e-3, 1e3);
  check_range(w, "major", major, 1e-3, 1e3);
  check_range(w, "length", length, 1e-3, 1e3);
  check_range(w, "side", side, 1e-3, 1e3);
  if (kind == ShapeKind::torus && !(major > radius))
    throw ConfigError(w + ": torus needs major (" + std::to_string(major) + ") > radius (" +
                      std::to_string(radius) + ")");
}

std::vector<SpectrumGroup> group_eigenvalues(const std::vector<double>& sorted, double rel_tol) {
  std::vector<SpectrumGroup> groups;
  for (double v : sorted) {
    if (!groups.empty() && std::fabs(v - groups.back().value) <= rel_tol * std::fabs(v)) {
      ++groups.back().multiplicity;
    } else {
      groups.push_back({v, 1});
    }
  }
  return groups;
}

}  // namespace sgnlf::spectral
