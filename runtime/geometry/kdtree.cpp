// k-d tree: median split on the axis of largest extent, leaves of ≤ leaf_size points,
// depth-first search that visits the near child first and prunes the far child by the
// distance to the splitting plane.
#include "geometry/kdtree.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <limits>
#include <numeric>

#include "core/error.hpp"

namespace sgnlf::geometry {

KdTree::KdTree(const std::vector<Point3f>& points, int leaf_size)
    : points_(points), order_(points.size()), leaf_size_(std::max(1, leaf_size)) {
  require(points.size() < size_t(std::numeric_limits<uint32_t>::max()),
          "KdTree: too many points (" + std::to_string(points.size()) + ")");
  for (size_t i = 0; i < points_.size(); ++i)
    if (!points_[i].allFinite())
      throw Error("KdTree: point " + std::to_string(i) + " is not finite");
  std::iota(order_.begin(), order_.end(), 0u);
  nodes_.reserve(2 * points_.size() / leaf_size_ + 2);
  if (!points_.empty()) build(0, uint32_t(points_.size()));
}

int32_t KdTree::build(uint32_t begin, uint32_t end) {
  const int32_t id = int32_t(nodes_.size());
  nodes_.push_back(Node{begin, end});
  if (end - begin <= uint32_t(leaf_size_)) return id;

  Point3f lo = points_[begin], hi = points_[begin];
  for (uint32_t i = begin + 1; i < end; ++i) {
    lo = lo.cwiseMin(points_[i]);
    hi = hi.cwiseMax(points_[i]);
  }
  int axis;
  (hi - lo).maxCoeff(&axis);
  if (hi[axis] == lo[axis]) return id;  // all points identical: keep as one leaf

  // Sort an index permutation and apply it to points_ and order_ together.
  const uint32_t mid = begin + (end - begin) / 2;
  std::vector<uint32_t> perm(end - begin);
  std::iota(perm.begin(), perm.end(), begin);
  std::nth_element(perm.begin(), perm.begin() + (mid - begin), perm.end(),
                   [&](uint32_t a, uint32_t b) { return points_[a][axis] < points_[b][axis]; });
  std::vector<Point3f> p(end - begin);
  std::vector<uint32_t> o(end - begin);
  for (size_t k = 0; k < perm.size(); ++k) {
    p[k] = points_[perm[k]];
    o[k] = order_[perm[k]];
  }
  std::copy(p.begin(), p.end(), points_.begin() + begin);
  std::copy(o.begin(), o.end(), order_.begin() + begin);

  // Left holds coordinates ≤ split, right ≥ split (ties may sit on both sides; the search
  // only relies on this ordering).
  const float split = points_[mid][axis];
  const int32_t left = build(begin, mid);
  const int32_t right = build(mid, end);
  Node& n = nodes_[id];
  n.axis = axis;
  n.split = split;
  n.left = left;
  n.right = right;
  return id;
}

void KdTree::search(int32_t node_id, const Point3f& q, float cell_sq, Point3f& off, float& best,
                    uint32_t& best_i) const {
  const Node& n = nodes_[node_id];
  if (n.left < 0) {
    for (uint32_t i = n.begin; i < n.end; ++i) {
      const float d = squared_distance(q, points_[i]);
      if (d < best || (d == best && order_[i] < order_[best_i])) {
        best = d;
        best_i = i;
      }
    }
    return;
  }
  const float diff = q[n.axis] - n.split;
  const int32_t near_child = diff <= 0.f ? n.left : n.right;
  const int32_t far_child = diff <= 0.f ? n.right : n.left;
  search(near_child, q, cell_sq, off, best, best_i);
  // The far side's cell lies at least |diff| away along this axis (replacing the offset the
  // query had along it before); ≤ keeps ties exact (an equally near point is still visited).
  const float old = off[n.axis];
  const float far_sq = cell_sq - old * old + diff * diff;
  if (far_sq <= best) {
    off[n.axis] = diff;
    search(far_child, q, far_sq, off, best, best_i);
    off[n.axis] = old;
  }
}

float KdTree::nearest(const Point3f& q, uint32_t* index) const {
  if (points_.empty()) throw Error("KdTree::nearest: the tree holds no points");
  if (!q.allFinite()) throw Error("KdTree::nearest: query point is not finite");
  float best = std::numeric_limits<float>::infinity();
  uint32_t best_i = 0;
  Point3f off = Point3f::Zero();
  search(0, q, 0.f, off, best, best_i);
  if (index) *index = order_[best_i];
  return best;
}

void KdTree::collect(int32_t node_id, const Point3f& q, float cell_sq, Point3f& off,
                     float r_sq, std::vector<uint32_t>& out) const {
  const Node& n = nodes_[node_id];
  if (n.left < 0) {
    for (uint32_t i = n.begin; i < n.end; ++i)
      if (squared_distance(q, points_[i]) <= r_sq) out.push_back(order_[i]);
    return;
  }
  // As in search(): the near child shares the query's cell bound, the far child's bound grows
  // by the offset to the splitting plane along this axis.
  const float diff = q[n.axis] - n.split;
  const int32_t near_child = diff <= 0.f ? n.left : n.right;
  const int32_t far_child = diff <= 0.f ? n.right : n.left;
  collect(near_child, q, cell_sq, off, r_sq, out);
  const float old = off[n.axis];
  const float far_sq = cell_sq - old * old + diff * diff;
  // The bound is rounded in float: a small slack only visits more cells (the leaf test above
  // decides), so a point exactly on the sphere is never lost to rounding of the bound.
  if (far_sq <= r_sq * (1.f + 1e-5f)) {
    off[n.axis] = diff;
    collect(far_child, q, far_sq, off, r_sq, out);
    off[n.axis] = old;
  }
}

void KdTree::radius_search(const Point3f& q, float radius, std::vector<uint32_t>& out) const {
  out.clear();
  if (points_.empty()) throw Error("KdTree::radius_search: the tree holds no points");
  if (!q.allFinite()) throw Error("KdTree::radius_search: query point is not finite");
  if (!(std::isfinite(radius) && radius >= 0.f))
    throw Error("KdTree::radius_search: radius " + std::to_string(radius) +
                " (must be finite and >= 0)");
  Point3f off = Point3f::Zero();
  collect(0, q, 0.f, off, radius * radius, out);
  std::sort(out.begin(), out.end());
}

void KdTree::nearest_all(const std::vector<Point3f>& queries, std::vector<float>& out_sq) const {
  out_sq.resize(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) out_sq[i] = nearest(queries[i]);
}

}  // namespace sgnlf::geometry
