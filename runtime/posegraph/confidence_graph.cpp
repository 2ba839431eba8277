// build_confidence_graph (see confidence_graph.hpp).
#include "posegraph/confidence_graph.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <thread>

#include "core/error.hpp"
#include "posegraph/candidate_pairs.hpp"
#include "posegraph/pair_matching.hpp"
#include "posegraph/spatial_consistency.hpp"

namespace sgnlf::posegraph {
namespace {

// Step 2: the frame's match points (LiDAR frame) and its matching data in the world.
struct FrameData {
  std::vector<Vec3> p_lidar;  // the match points in their own LiDAR frame (for α)
  FrameMatchData match;
};

FrameData frame_data(const FrameCloud& cloud, const Pose& T_world_lidar,
                     const FeatureProvider& features, const ConfidenceGraphConfig& cfg,
                     uint32_t frame) {
  const auto idx = subsample_indices(cloud.size(), cfg.match_points, cfg.seed, frame);
  std::vector<Vec3> p;
  std::vector<geometry::Point3f> x;
  p.reserve(idx.size());
  x.reserve(idx.size());
  for (uint32_t k : idx) {
    p.push_back(cloud.points[k].cast<double>());
    x.push_back((T_world_lidar * p.back()).cast<float>());
  }
  std::vector<float> f = unit_features(features, x);
  return FrameData{std::move(p),
                   make_frame_match_data(std::move(x), std::move(f), features.dim,
                                         cfg.coarse_voxel_m)};
}

// Step 3 for one pair.
void evaluate_pair(const FrameData& A, const FrameData& B, const ConfidenceGraphConfig& cfg,
                   size_t frames, PairReport& r) {
  const CoarseToFineParams params{float(cfg.coarse_radius_m), float(cfg.fine_radius_m),
                                  cfg.coarse_to_fine};
  const PairMatches m = match_frames(A.match, B.match, params);
  r.coarse_matches = m.coarse;
  r.matches = m.fine.size();
  double sum = 0.0;
  std::vector<Vec3> p, q;
  p.reserve(m.fine.size());
  q.reserve(m.fine.size());
  for (const auto& fm : m.fine) {
    sum += fm.cosine;
    p.push_back(A.p_lidar[fm.a]);
    q.push_back(B.p_lidar[fm.b]);
  }
  r.compatibility = m.fine.empty() ? 0.0 : sum / double(m.fine.size());
  const uint32_t stream = uint32_t(size_t(r.i) * frames + size_t(r.j));
  r.alpha = spatial_consistency(p, q, cfg.sigma_d_m, cfg.max_alpha_pairs, cfg.seed, stream);
  const double smaller = double(std::min(A.p_lidar.size(), B.p_lidar.size()));
  r.valid = r.matches >= size_t(cfg.min_matches) &&
            double(r.matches) >= cfg.min_match_fraction * smaller;
}

// Runs body(k) for k in [0, n) on `threads` threads (stride split); rethrows the first failure.
template <class F>
void parallel_for(size_t n, int threads, F body) {
  const size_t t_count = std::max<size_t>(1, std::min(size_t(threads), n));
  std::vector<std::exception_ptr> failed(t_count);
  auto work = [&](size_t first) {
    try {
      for (size_t k = first; k < n; k += t_count) body(k);
    } catch (...) {
      failed[first] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (size_t t = 1; t < t_count; ++t) pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool) th.join();
  for (const auto& f : failed)
    if (f) std::rethrow_exception(f);
}

}  // namespace

size_t ConfidenceGraph::non_adjacent_edges() const {
  size_t n = 0;
  for (const auto& p : pairs) n += (p.kept && !p.sequential) ? 1 : 0;
  return n;
}

ConfidenceGraph build_confidence_graph(const std::vector<FrameCloud>& clouds,
                                       const std::vector<Pose>& T,
                                       const FeatureProvider& features,
                                       const ConfidenceGraphConfig& cfg) {
  cfg.validate();
  require(clouds.size() == T.size(), "build_confidence_graph: " + std::to_string(T.size()) +
                                         " poses for " + std::to_string(clouds.size()) +
                                         " frame clouds");
  require(clouds.size() >= 2, "build_confidence_graph: needs at least two frames, got " +
                                  std::to_string(clouds.size()));
  ConfidenceGraph g;
  g.frames = clouds.size();
  const auto candidates = candidate_pairs(T, cfg.sequential_offsets, cfg.candidate_distance_m,
                                          cfg.min_index_gap);

  // Features on the calling thread, frame by frame (the provider may own a device queue).
  std::vector<FrameData> frames;
  frames.reserve(clouds.size());
  for (size_t k = 0; k < clouds.size(); ++k)
    frames.push_back(frame_data(clouds[k], T[k], features, cfg, uint32_t(k)));

  g.pairs.resize(candidates.size());
  for (size_t c = 0; c < candidates.size(); ++c) {
    g.pairs[c].i = candidates[c].i;
    g.pairs[c].j = candidates[c].j;
    g.pairs[c].sequential = candidates[c].sequential;
    g.pairs[c].centre_distance_m = candidates[c].centre_distance_m;
  }
  parallel_for(g.pairs.size(), cfg.threads, [&](size_t c) {
    PairReport& r = g.pairs[c];
    evaluate_pair(frames[size_t(r.i)], frames[size_t(r.j)], cfg, clouds.size(), r);
  });

  // Step 4: the adaptive threshold over the valid sequential pairs (sums in pair order).
  double sum = 0.0, sum_alpha = 0.0;
  size_t count = 0;
  for (const auto& r : g.pairs)
    if (r.sequential && r.valid) sum += r.compatibility, sum_alpha += r.alpha, ++count;
  if (count > 0) {
    g.sequential_mean = sum / double(count);
    double var = 0.0;
    for (const auto& r : g.pairs)
      if (r.sequential && r.valid) var += std::pow(r.compatibility - g.sequential_mean, 2);
    g.sequential_std = std::sqrt(var / double(count));
    g.threshold = g.sequential_mean + cfg.kappa * g.sequential_std;
  } else {
    g.threshold = std::numeric_limits<double>::infinity();
  }
  const double fallback_alpha = count > 0 ? sum_alpha / double(count) : 1.0;

  // Step 5: sequential edges first (every one), then the kept non-adjacent ones.
  for (auto& r : g.pairs) {
    if (!r.sequential) continue;
    r.kept = true;
    r.weight = !cfg.alpha_weights ? 1.0 : (r.valid ? r.alpha : fallback_alpha);
    g.edges.push_back(Edge{r.i, r.j, r.weight});
  }
  for (auto& r : g.pairs) {
    if (r.sequential || !r.valid) continue;
    r.kept = !cfg.compatibility_test || r.compatibility >= g.threshold;
    if (!r.kept) continue;
    r.weight = cfg.alpha_weights ? r.alpha : 1.0;
    g.edges.push_back(Edge{r.i, r.j, r.weight});
  }
  validate_edges(g.edges, int(g.frames));
  return g;
}

}  // namespace sgnlf::posegraph
