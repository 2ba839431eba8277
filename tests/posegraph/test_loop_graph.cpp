// The confidence-aware pose graph on a simulated kitti360-loop (frames 31–35 revisit 0–4),
// built from the ground-truth poses with the STAND-IN features (posegraph/standin_features.hpp):
// its non-adjacent edges must connect frames that truly overlap (loop_fixture.hpp defines the
// overlap), precision ≥ 0.9 and recall ≥ 0.8 against the non-adjacent pairs with overlap ≥ 30 %.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <cstdlib>
#include <fstream>

#include "core/config.hpp"
#include "loop_fixture.hpp"
#include "posegraph/confidence_graph.hpp"
#include "posegraph/standin_features.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

constexpr size_t kPoints = 4000;
constexpr double kOverlap = 0.3;

// The test's graph settings: the defaults, except that every non-sequential pair is a candidate
// (min_index_gap 0), the compatibility test is on and κ = −6. Measured on this fixture (2 Hz,
// 36 frames): the sequential E have mean 0.927 and std 0.0115, and pairs 15–30 m apart that
// overlap by 30–60 % score E ≈ 0.85–0.90, so κ = −6 admits them; κ = −4 keeps only 76 % of them
// (min_match_fraction does the rest of the overlap test).
ConfidenceGraphConfig test_graph_config() {
  ConfidenceGraphConfig c;
  c.min_index_gap = 0;
  c.compatibility_test = true;
  c.kappa = -6.0;
  c.threads = 2;
  return c;
}

struct LoopFixture {
  std::shared_ptr<const std::vector<FrameCloud>> clouds = test::loop_clouds(kPoints);
  std::vector<std::vector<double>> overlap = test::gt_overlap(*clouds);
  std::vector<Pose> gt = gt_poses(test::loop_sequence());
};

const LoopFixture& fixture() {
  static const LoopFixture f;
  return f;
}

bool is_sequential(const ConfidenceGraphConfig& cfg, size_t i, size_t j) {
  for (int o : cfg.sequential_offsets)
    if (j - i == size_t(o)) return true;
  return false;
}

struct Score {
  size_t positives = 0, found = 0, true_found = 0;
  bool loop_closed = false;
  double precision() const { return double(true_found) / double(std::max<size_t>(found, 1)); }
  double recall() const { return double(true_found) / double(std::max<size_t>(positives, 1)); }
};

Score score(const ConfidenceGraph& g, const ConfidenceGraphConfig& cfg) {
  const auto& f = fixture();
  Score s;
  const size_t n = f.clouds->size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      if (!is_sequential(cfg, i, j) && f.overlap[i][j] >= kOverlap) ++s.positives;
  for (const auto& r : g.pairs) {
    if (r.sequential || !r.kept) continue;
    ++s.found;
    s.true_found += f.overlap[size_t(r.i)][size_t(r.j)] >= kOverlap;
    s.loop_closed |= r.i <= 4 && r.j >= 31;
  }
  return s;
}

}  // namespace

TEST_CASE("non-adjacent edges from the GT poses of kitti360-loop connect overlapping frames",
          "[posegraph][confidence][loop]") {
  const auto& f = fixture();
  const ConfidenceGraphConfig cfg = test_graph_config();
  const auto g = build_confidence_graph(*f.clouds, f.gt, standin_fourier_features({}), cfg);
  const Score s = score(g, cfg);
  WARN("kitti360-loop from GT poses: " << s.found << " non-adjacent edges, " << s.positives
                                       << " pairs with overlap >= 30 %: precision "
                                       << s.precision() << ", recall " << s.recall()
                                       << " (threshold " << g.threshold << ")");
  CHECK(s.positives > 20);
  CHECK(s.precision() >= 0.9);
  CHECK(s.recall() >= 0.8);
  CHECK(s.loop_closed);  // frames 31-35 revisit 0-4
}

TEST_CASE("mutants of the loop graph (kappa huge; no overlap or compatibility test) fail",
          "[posegraph][confidence][loop]") {
  const auto& f = fixture();
  ConfidenceGraphConfig huge = test_graph_config();
  huge.kappa = 1e6;
  const auto g = build_confidence_graph(*f.clouds, f.gt, standin_fourier_features({}), huge);
  CHECK(g.non_adjacent_edges() == 0);
  CHECK(score(g, huge).recall() < 0.8);
  // Without the match-fraction test and the compatibility test every candidate with 30
  // matches is kept: the precision criterion fails.
  ConfidenceGraphConfig loose = test_graph_config();
  loose.min_match_fraction = 0.0;
  loose.compatibility_test = false;
  const auto g2 = build_confidence_graph(*f.clouds, f.gt, standin_fourier_features({}), loose);
  WARN("without the overlap and compatibility tests: precision " << score(g2, loose).precision()
                                                                << ", recall "
                                                                << score(g2, loose).recall());
  CHECK(score(g2, loose).precision() < 0.9);
}

TEST_CASE("[report] candidate pairs of kitti360-loop under GT poses, several settings",
          "[.report]") {
  // Writes one JSON line per setting to $SGNLF_REPORT (default /tmp/sgnlf_loop_graph.jsonl):
  // every candidate's E, α, matches and ground-truth overlap.
  const char* env = std::getenv("SGNLF_REPORT");
  std::ofstream out(env ? env : "/tmp/sgnlf_loop_graph.jsonl");
  for (size_t points : {2000u, 4000u}) {
    const auto clouds = test::loop_clouds(points);
    const auto overlap = test::gt_overlap(*clouds);
    for (double lo : {0.5, 1.0})
      for (double fine : {0.5, 1.0})
        for (double voxel : {1.0, 2.0}) {
          ConfidenceGraphConfig c = test_graph_config();
          c.fine_radius_m = fine;
          c.coarse_voxel_m = voxel;
          c.candidate_distance_m = 60.0;
          StandinFeatureConfig sf;
          sf.min_wavelength_m = lo;
          const auto g = build_confidence_graph(*clouds, gt_poses(test::loop_sequence()),
                                                standin_fourier_features(sf), c);
          Json j = confidence_graph_json(g);
          for (auto& e : j["edges"]) e["overlap"] = overlap[e["i"].get<size_t>()][e["j"].get<size_t>()];
          Json all = Json::array();
          for (size_t a = 0; a < clouds->size(); ++a)
            for (size_t b = a + 1; b < clouds->size(); ++b) all.push_back(overlap[a][b]);
          out << Json{{"points", points}, {"min_wavelength", lo}, {"fine", fine},
                      {"voxel", voxel}, {"graph", j}, {"all_overlap", all}}.dump()
              << "\n";
        }
  }
}
