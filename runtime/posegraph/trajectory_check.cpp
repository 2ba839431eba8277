// check_trajectory (see trajectory_check.hpp).
#include "posegraph/trajectory_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::posegraph {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + long(m), v.end());
  const double hi = v[m];
  if (v.size() % 2 == 1) return hi;
  return 0.5 * (hi + *std::max_element(v.begin(), v.begin() + long(m)));
}

// Share of src's points within `r` of dst under T_dst_src, and their median NN distance.
std::pair<double, double> direction_overlap(const FrameCloud& src, const FrameCloud& dst,
                                            const Pose& T_dst_src, double r) {
  std::vector<double> d(src.size());
  size_t in = 0;
  for (size_t k = 0; k < src.size(); ++k) {
    const Vec3 q = T_dst_src * src.points[k].cast<double>();
    d[k] = std::sqrt(double(dst.tree.nearest(q.cast<float>())));
    in += d[k] <= r ? 1 : 0;
  }
  return {double(in) / double(src.size()), median(std::move(d))};
}

}  // namespace

void TrajectoryCheckConfig::validate() const {
  check_range("trajectory check", "inlier_distance_m", inlier_distance_m, 1e-3, 1e3);
  check_range("trajectory check", "edge_ratio", edge_ratio, 0.0, 1.0);
  check_range("trajectory check", "min_median_overlap", min_median_overlap, 0.0, 1.0);
  check_range("trajectory check", "jump_ratio", jump_ratio, 1.0, 1e6);
}

int TrajectoryCheck::suspect_edges() const {
  int n = 0;
  for (const auto& e : edges) n += e.suspect ? 1 : 0;
  return n;
}

Json TrajectoryCheck::to_json() const {
  Json suspect = Json::array();
  for (const auto& e : edges)
    if (e.suspect)
      suspect.push_back(Json{{"i", e.i}, {"j", e.j}, {"overlap", e.overlap},
                             {"median_distance_m", e.median_distance_m}});
  Json overlap = Json::array();
  for (const auto& e : edges) overlap.push_back(e.overlap);
  return Json{{"converged", converged}, {"reason", reason}, {"median_overlap", median_overlap},
              {"edges", edges.size()}, {"suspect_edges", suspect}, {"jumps", jumps},
              {"edge_overlap", overlap}};
}

TrajectoryCheck check_trajectory(const std::vector<FrameCloud>& clouds,
                                 const std::vector<Pose>& T, const std::vector<Edge>& edges,
                                 const TrajectoryCheckConfig& cfg) {
  cfg.validate();
  require(T.size() == clouds.size(), "check_trajectory: " + std::to_string(T.size()) +
                                         " poses for " + std::to_string(clouds.size()) + " frames");
  validate_edges(edges, int(clouds.size()));
  TrajectoryCheck out;
  std::vector<double> overlaps;
  for (const Edge& e : edges) {
    const Pose T_ji = T[size_t(e.j)].inverse() * T[size_t(e.i)];
    const auto a = direction_overlap(clouds[size_t(e.i)], clouds[size_t(e.j)], T_ji,
                                     cfg.inlier_distance_m);
    const auto b = direction_overlap(clouds[size_t(e.j)], clouds[size_t(e.i)], T_ji.inverse(),
                                     cfg.inlier_distance_m);
    EdgeOverlap o;
    o.i = e.i;
    o.j = e.j;
    o.overlap = 0.5 * (a.first + b.first);
    o.median_distance_m = 0.5 * (a.second + b.second);
    out.edges.push_back(o);
    overlaps.push_back(o.overlap);
  }
  out.median_overlap = median(overlaps);
  for (auto& e : out.edges) e.suspect = e.overlap < cfg.edge_ratio * out.median_overlap;
  // Jumps: a step between neighbours far longer than the trajectory's typical step.
  std::vector<double> steps;
  for (size_t k = 0; k + 1 < T.size(); ++k)
    steps.push_back((T[k + 1].translation() - T[k].translation()).norm());
  const double typical = median(steps);
  for (size_t k = 0; k < steps.size(); ++k)
    if (steps[k] > cfg.jump_ratio * typical + 1.0) out.jumps.push_back(int(k));
  char buf[160];
  if (out.median_overlap < cfg.min_median_overlap) {
    std::snprintf(buf, sizeof buf, "median edge overlap %.2f < %.2f: the scans do not register",
                  out.median_overlap, cfg.min_median_overlap);
    out.reason = buf;
  } else if (out.suspect_edges() > 0) {
    std::snprintf(buf, sizeof buf, "%d of %zu edges overlap less than %.2f x the median %.2f",
                  out.suspect_edges(), out.edges.size(), cfg.edge_ratio, out.median_overlap);
    out.reason = buf;
  }
  if (!out.jumps.empty()) {
    std::snprintf(buf, sizeof buf, "%s%zu neighbour jump(s) > %.1f x the median step + 1 m",
                  out.reason.empty() ? "" : "; ", out.jumps.size(), cfg.jump_ratio);
    out.reason += buf;
  }
  out.converged = out.reason.empty();
  return out;
}

}  // namespace sgnlf::posegraph
