// Exact nearest-neighbour search in 3-D (a k-d tree over float points), shared by the Chamfer
// distance and F-score (metrics, protocol §4) and the geometric pose optimiser (posegraph,
// method.md §3). Exact: every query returns the true minimum squared distance, computed in
// float as the peers' CUDA chamfer kernel does; tests compare it with a brute-force search.
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace sgnlf::geometry {

using Point3f = Eigen::Vector3f;

// Squared Euclidean distance in float, the one distance function shared by the tree and the
// brute-force reference of the tests (so both agree bit for bit).
inline float squared_distance(const Point3f& a, const Point3f& b) {
  const float dx = a.x() - b.x(), dy = a.y() - b.y(), dz = a.z() - b.z();
  return dx * dx + dy * dy + dz * dz;
}

class KdTree {
 public:
  // Builds over a copy of `points` (may be empty: every query then throws).
  explicit KdTree(const std::vector<Point3f>& points, int leaf_size = 12);

  size_t size() const { return points_.size(); }
  // Squared distance to the nearest point and its index in the input order.
  float nearest(const Point3f& q, uint32_t* index = nullptr) const;
  // nearest() for every query; `out_sq` is resized to queries.size().
  void nearest_all(const std::vector<Point3f>& queries, std::vector<float>& out_sq) const;
  // Indices (input order, ascending) of every point p with squared_distance(q, p) ≤ radius²
  // (radius² computed in float; exact, the same test a brute-force scan makes). `out` is
  // cleared first. Throws sgnlf::Error for an empty tree, a non-finite query or a radius that
  // is negative or not finite.
  void radius_search(const Point3f& q, float radius, std::vector<uint32_t>& out) const;

 private:
  struct Node {
    uint32_t begin, end;   // range in points_ (leaf) or of the subtree
    int32_t left = -1, right = -1;  // children (-1: leaf)
    int axis = 0;
    float split = 0.f;
  };
  int32_t build(uint32_t begin, uint32_t end);
  // `off` holds, per axis, the query's offset from the node's cell along the splits taken so
  // far and `cell_sq` its squared length: a lower bound on the distance to every point of the
  // node (Arya & Mount's incremental distance), which prunes far cells that one splitting
  // plane alone would not.
  void search(int32_t node, const Point3f& q, float cell_sq, Point3f& off, float& best,
              uint32_t& best_i) const;

  void collect(int32_t node, const Point3f& q, float cell_sq, Point3f& off, float r_sq,
               std::vector<uint32_t>& out) const;

  std::vector<Point3f> points_;   // permuted so that each leaf is contiguous
  std::vector<uint32_t> order_;   // points_[k] = input[order_[k]]
  std::vector<Node> nodes_;
  int leaf_size_;
};

}  // namespace sgnlf::geometry
