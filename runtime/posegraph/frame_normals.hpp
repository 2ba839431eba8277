// Surface normals for a frame's points, for the point-to-plane direction term
// (point_to_plane.hpp). Each normal is the smallest-eigenvalue eigenvector of the covariance of
// the scan's points within `radius_m` of the point (searched in the FULL scan, not the
// subsample: a 4000-point subsample of a 32-beam scan is too sparse to fit planes). A point
// whose neighbourhood is too small or not planar gets a zero normal, which the point-to-plane
// term skips.
#pragma once
#include <vector>

#include "geometry/kdtree.hpp"

namespace sgnlf::posegraph {

struct NormalOptions {
  double radius_m = 1.0;        // neighbourhood radius in the full scan
  int min_neighbours = 6;       // fewer → zero normal
  // Planarity: λ_min / λ_mid of the covariance at most this (a line or a blob has a larger
  // ratio, and its "normal" is arbitrary).
  double max_flatness = 0.3;
  // The keys and ranges (core/config_fields.hpp); validate() checks the same bounds.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("radius_m", s.radius_m, 1e-6, 100.0);
    v("min_neighbours", s.min_neighbours, 3, 1 << 20);
    v("max_flatness", s.max_flatness, 1e-9, 1.0);
  }
  void validate() const;
};

// Unit normals (or zero) of `points`, searched among `scan`, both in the same frame. Oriented
// towards the sensor at the origin (n·p ≤ 0), so that a normal's sign is reproducible.
std::vector<geometry::Point3f> estimate_normals(const std::vector<geometry::Point3f>& points,
                                                const std::vector<geometry::Point3f>& scan,
                                                const NormalOptions& o);

}  // namespace sgnlf::posegraph
