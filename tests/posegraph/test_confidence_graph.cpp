// The confidence graph on small synthetic scenes: spatial consistency separates clean from
// corrupted correspondences (and a mutant score does not), the weighted graph loss gradient
// against central differences, config and input errors, determinism for any thread count, and
// the JSON and SVG writers.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "io/pose_graph_svg.hpp"
#include "posegraph/confidence_graph.hpp"
#include "posegraph/graph_loss.hpp"
#include "posegraph/pair_matching.hpp"
#include "posegraph/pose_adam.hpp"
#include "posegraph/spatial_consistency.hpp"
#include "posegraph/staged_graph_run.hpp"
#include "posegraph/standin_features.hpp"
#include "smooth_scene.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

// Five frames along x (1.5 m apart) seeing the same smooth surfaces, each from its own sample.
struct SmallScene {
  std::vector<FrameCloud> clouds;
  std::vector<Pose> T;
};

SmallScene small_scene(int frames = 5, size_t points = 1500) {
  SmallScene s;
  for (int k = 0; k < frames; ++k) {
    const Pose T = exp_se3((Vec6() << 0.0, 0.0, 0.05 * k, 1.5 * k, 0.3 * k, 0.0).finished());
    s.clouds.push_back(test::cloud_seen_from(test::smooth_world_points(points, 100 + k), T));
    s.T.push_back(T);
  }
  return s;
}

FrameMatchData match_data(const FrameCloud& c, const Pose& T, const FeatureProvider& f) {
  std::vector<geometry::Point3f> x;
  for (const auto& p : c.points) x.push_back((T * p.cast<double>()).cast<float>());
  auto feats = unit_features(f, x);
  return make_frame_match_data(std::move(x), std::move(feats), f.dim, 2.0);
}

// The test's own α (all pairs) with a pluggable per-pair score.
template <class Score>
double mean_over_pairs(const std::vector<Vec3>& p, const std::vector<Vec3>& q, Score score) {
  double s = 0;
  size_t n = 0;
  for (size_t a = 0; a < p.size(); ++a)
    for (size_t b = a + 1; b < p.size(); ++b) s += score(p[a], p[b], q[a], q[b]), ++n;
  return s / double(n);
}

}  // namespace

TEST_CASE("injected wrong matches lower alpha; a mutant score does not notice them",
          "[posegraph][confidence]") {
  const auto s = small_scene(2);
  const auto f = standin_fourier_features({});
  const auto A = match_data(s.clouds[0], s.T[0], f), B = match_data(s.clouds[1], s.T[1], f);
  const auto m = match_frames(A, B, {4.f, 1.f, true});
  REQUIRE(m.fine.size() > 200);
  std::vector<Vec3> p, q, q_bad;
  Rng rng(31);
  for (const auto& fm : m.fine) {
    p.push_back(s.clouds[0].points[fm.a].cast<double>());
    q.push_back(s.clouds[1].points[fm.b].cast<double>());
    // One match in five re-pointed at a random point of frame 1.
    q_bad.push_back(rng.below(5) == 0
                        ? s.clouds[1].points[rng.below(uint32_t(s.clouds[1].size()))].cast<double>()
                        : q.back());
  }
  const double clean = spatial_consistency(p, q, 0.5, 20000, 1, 0);
  const double bad = spatial_consistency(p, q_bad, 0.5, 20000, 1, 0);
  WARN("alpha clean " << clean << ", with 20 % wrong matches " << bad << " (" << p.size()
                      << " matches)");
  CHECK(clean > 0.8);
  CHECK(bad < clean - 0.2);
  // The library's draws agree with the test's own all-pairs mean.
  const auto P = [](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    return pair_consistency(a, b, c, d, 0.5);
  };
  CHECK(clean == Approx(mean_over_pairs(p, q, P)).margin(0.01));
  CHECK(bad == Approx(mean_over_pairs(p, q_bad, P)).margin(0.01));
  // Mutant: P from the distances within frame i only (q ignored) cannot tell the sets apart.
  const auto mutant = [](const Vec3& a, const Vec3& b, const Vec3&, const Vec3&) {
    const double r = (a - b).norm() - (a - b).norm();
    return std::exp(-r * r / 0.5);
  };
  CHECK_FALSE(mean_over_pairs(p, q_bad, mutant) < mean_over_pairs(p, q, mutant));
}

TEST_CASE("alpha falls when the poses the matches were found under are wrong",
          "[posegraph][confidence]") {
  const auto s = small_scene(2);
  const auto f = standin_fourier_features({});
  auto alpha_under = [&](const Pose& T1) {
    const auto m = match_frames(match_data(s.clouds[0], s.T[0], f),
                                match_data(s.clouds[1], T1, f), {4.f, 1.f, true});
    std::vector<Vec3> p, q;
    for (const auto& fm : m.fine) {
      p.push_back(s.clouds[0].points[fm.a].cast<double>());
      q.push_back(s.clouds[1].points[fm.b].cast<double>());
    }
    return spatial_consistency(p, q, 0.5, 20000, 1, 0);
  };
  const double good = alpha_under(s.T[1]);
  const double off = alpha_under(corrected_pose(s.T[1], (Vec6() << 0, 0, 0.1, 1.0, -0.5, 0).finished()));
  WARN("alpha under the true poses " << good << ", under a 0.1 rad / 1.1 m error " << off);
  CHECK(off < good - 0.1);
}

TEST_CASE("weighted confidence-graph loss: analytic pose gradients match central differences",
          "[posegraph][confidence][gradient]") {
  // L_graph = Σ α^ij · CD^ij over a graph with a non-adjacent edge, α held constant; τ = 0.
  auto s = small_scene(3, 800);
  auto clouds = std::make_shared<const std::vector<FrameCloud>>(s.clouds);
  const std::vector<Edge> edges = {{0, 1, 0.7}, {1, 2, 0.35}, {0, 2, 0.55}};
  const GraphLoss loss(clouds, edges);
  const std::vector<Vec6> xi = {(Vec6() << 0.02, -0.01, 0.03, 0.2, -0.1, 0.05).finished(),
                                (Vec6() << -0.01, 0.02, -0.02, -0.1, 0.15, 0.0).finished(),
                                (Vec6() << 0.0, 0.01, 0.04, 0.1, 0.1, -0.05).finished()};
  std::vector<PoseGrad> g;
  auto f = [&](const std::vector<Vec6>& x) {
    std::vector<Pose> T;
    for (int k = 0; k < 3; ++k) T.push_back(corrected_pose(s.T[size_t(k)], x[size_t(k)]));
    return loss(T, 0.0, g);
  };
  f(xi);
  Eigen::VectorXd analytic(18), numeric(18);
  for (int k = 0; k < 3; ++k)
    analytic.segment<6>(6 * k) = decoupled_gradient(s.T[size_t(k)], xi[size_t(k)], g[size_t(k)]);
  const double h = 1e-6;
  for (int c = 0; c < 18; ++c) {
    auto plus = xi, minus = xi;
    plus[size_t(c / 6)][c % 6] += h;
    minus[size_t(c / 6)][c % 6] -= h;
    numeric[c] = (f(plus) - f(minus)) / (2 * h);
  }
  INFO("analytic " << analytic.transpose() << "\nnumeric  " << numeric.transpose());
  CHECK((analytic - numeric).norm() / numeric.norm() < 1e-5);
  CHECK(numeric.norm() > 0.05);
  // The weights matter: the same graph with the non-adjacent edge at weight 1 differs.
  const GraphLoss unweighted(clouds, {{0, 1, 0.7}, {1, 2, 0.35}, {0, 2, 1.0}});
  std::vector<PoseGrad> g2;
  std::vector<Pose> T;
  for (int k = 0; k < 3; ++k) T.push_back(corrected_pose(s.T[size_t(k)], xi[size_t(k)]));
  CHECK(unweighted(T, 0.0, g2) != loss(T, 0.0, g));
}

TEST_CASE("confidence graph on a small scene: sequential edges always, weights α, report",
          "[posegraph][confidence]") {
  const auto s = small_scene();
  ConfidenceGraphConfig c;
  c.sequential_offsets = {1};
  c.min_index_gap = 0;
  c.compatibility_test = true;
  c.candidate_distance_m = 4.0;  // (i, i+2) at 3.1 m are candidates, (i, i+3) at 4.6 m not
  c.min_matches = 10;
  c.kappa = -3.0;
  const auto g = build_confidence_graph(s.clouds, s.T, standin_fourier_features({}), c);
  REQUIRE(g.pairs.size() == 4 + 3);
  size_t seq = 0;
  for (const auto& r : g.pairs) {
    INFO("pair (" << r.i << ", " << r.j << ")");
    CHECK(r.j - r.i <= 2);
    CHECK(r.sequential == (r.j - r.i == 1));
    CHECK(r.valid);
    CHECK(r.alpha > 0.5);
    CHECK(r.compatibility > 0.9);
    if (r.sequential) CHECK(r.kept);
    if (r.kept) CHECK(r.weight == r.alpha);
    seq += r.sequential;
  }
  CHECK(seq == 4);
  CHECK(g.edges.size() == 4 + g.non_adjacent_edges());
  CHECK(g.non_adjacent_edges() > 0);
  // κ huge (mutant of the threshold): no non-adjacent edge survives.
  c.kappa = 1e6;
  CHECK(build_confidence_graph(s.clouds, s.T, standin_fourier_features({}), c)
            .non_adjacent_edges() == 0);
  // Ablations: without the compatibility test every valid candidate is kept; without α every
  // weight is 1.
  c.compatibility_test = false;
  c.alpha_weights = false;
  const auto g2 = build_confidence_graph(s.clouds, s.T, standin_fourier_features({}), c);
  CHECK(g2.non_adjacent_edges() == 3);
  for (const auto& e : g2.edges) CHECK(e.weight == 1.0);
}

TEST_CASE("confidence graph is bit-identical for any thread count", "[posegraph][confidence]") {
  const auto s = small_scene();
  ConfidenceGraphConfig c;
  c.min_matches = 10;
  c.min_index_gap = 0;
  c.compatibility_test = true;
  c.kappa = -1.0;
  auto run = [&](int threads) {
    c.threads = threads;
    return build_confidence_graph(s.clouds, s.T, standin_fourier_features({}), c);
  };
  const auto a = run(1), b = run(3);
  CHECK(confidence_graph_json(a).dump() == confidence_graph_json(b).dump());
  REQUIRE(a.edges.size() == b.edges.size());
  for (size_t k = 0; k < a.edges.size(); ++k) {
    CHECK(a.edges[k].i == b.edges[k].i);
    CHECK(a.edges[k].j == b.edges[k].j);
    CHECK(a.edges[k].weight == b.edges[k].weight);
  }
}

TEST_CASE("confidence graph config: JSON, defaults, errors naming the key",
          "[posegraph][confidence][config]") {
  CHECK_NOTHROW(ConfidenceGraphConfig{}.validate());
  const auto c = ConfidenceGraphConfig::from_json(
      Json{{"kappa", 0.5}, {"sigma_d_m", 0.3}, {"sequential_offsets", {1}}}, "graph");
  CHECK(c.kappa == 0.5);
  CHECK(c.sigma_d_m == 0.3);
  CHECK(c.sequential_offsets == std::vector<int>{1});
  CHECK(c.fine_radius_m == ConfidenceGraphConfig{}.fine_radius_m);
  // Round trip.
  const auto d = ConfidenceGraphConfig::from_json(c.to_json(), "round trip");
  CHECK(d.to_json() == c.to_json());
  auto error_of = [](const Json& j) {
    try {
      ConfidenceGraphConfig::from_json(j, "graph.json");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error_of(Json{{"kapa", 1.0}}), Catch::Contains("unknown key(s) 'kapa'"));
  CHECK_THAT(error_of(Json{{"sigma_d_m", 0.0}}), Catch::Contains("sigma_d_m"));
  CHECK_THAT(error_of(Json{{"sequential_offsets", Json::array()}}), Catch::Contains("sequential_offsets"));
  CHECK_THAT(error_of(Json{{"sequential_offsets", {1, 1}}}), Catch::Contains("repeated"));
  CHECK_THAT(error_of(Json{{"min_matches", 1}}), Catch::Contains("min_matches"));
  CHECK_THAT(error_of(Json{{"coarse_voxel_m", -2.0}}), Catch::Contains("coarse_voxel_m"));
  CHECK_THAT(error_of(Json{{"reevaluate_every", 0}}), Catch::Contains("reevaluate_every"));
  CHECK_THAT(error_of(Json{{"threads", 0}}), Catch::Contains("threads"));
  CHECK_THAT(error_of(Json{{"kappa", "high"}}), Catch::Contains("kappa"));
  CHECK_THAT(error_of(Json{{"match_points", -5}}), Catch::Contains("match_points"));
  CHECK_THAT(error_of(Json::array()), Catch::Contains("graph.json"));
}

TEST_CASE("confidence graph rejects bad inputs with clear errors", "[posegraph][confidence]") {
  const auto s = small_scene(3, 300);
  const auto f = standin_fourier_features({});
  const ConfidenceGraphConfig c;
  auto T = s.T;
  T.pop_back();
  CHECK_THROWS_WITH(build_confidence_graph(s.clouds, T, f, c),
                    Catch::Contains("2 poses for 3 frame clouds"));
  CHECK_THROWS_AS(build_confidence_graph({s.clouds[0]}, {s.T[0]}, f, c), Error);
  T = s.T;
  T[1].matrix()(0, 3) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(build_confidence_graph(s.clouds, T, f, c), Catch::Contains("frame 1"));
  FeatureProvider wrong = f;
  wrong.dim = f.dim + 1;
  CHECK_THROWS_WITH(build_confidence_graph(s.clouds, s.T, wrong, c),
                    Catch::Contains("values for"));
  ConfidenceGraphConfig bad;
  bad.fine_radius_m = 0.0;
  CHECK_THROWS_AS(build_confidence_graph(s.clouds, s.T, f, bad), ConfigError);
}

TEST_CASE("graph JSON and SVG writers", "[posegraph][confidence][io]") {
  const auto s = small_scene();
  ConfidenceGraphConfig c;
  c.min_matches = 10;
  c.min_index_gap = 0;
  const auto g = build_confidence_graph(s.clouds, s.T, standin_fourier_features({}), c);
  const Json j = confidence_graph_json(g);
  CHECK(j.at("frames") == 5);
  CHECK(j.at("edges").size() == g.pairs.size());
  CHECK(j.at("non_adjacent_edges") == g.non_adjacent_edges());
  const Json& e0 = j.at("edges").at(0);
  for (const char* key : {"i", "j", "sequential", "E", "alpha", "weight", "n_matches", "kept"})
    CHECK(e0.contains(key));
  CHECK(j.at("threshold").get<double>() == g.threshold);

  const auto dir = std::filesystem::temp_directory_path() / "sgnlf_posegraph_svg_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "graph.svg").string();
  std::vector<io::SvgGraphEdge> edges;
  for (const auto& r : g.pairs)
    if (r.kept) edges.push_back({r.i, r.j, r.weight, r.sequential});
  io::write_pose_graph_svg(path, "graph <test>", s.T, edges, s.T);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string svg = text.str();
  CHECK(svg.rfind("<svg", 0) == 0);
  CHECK(svg.find("graph &lt;test&gt;") != std::string::npos);
  size_t lines = 0;
  for (size_t p = svg.find("<line x1"); p != std::string::npos; p = svg.find("<line x1", p + 1))
    ++lines;
  CHECK(lines == edges.size() + 2 + 1);  // edges, two legend swatches, the scale bar
  CHECK_THROWS_AS(io::write_pose_graph_svg(path, "t", s.T, {{0, 9, 1.0, false}}), Error);
  CHECK_THROWS_AS(io::write_pose_graph_svg(path, "t", s.T, {{0, 1, -1.0, true}}), Error);
  CHECK_THROWS_AS(io::write_pose_graph_svg((dir / "no/such/dir.svg").string(), "t", s.T, edges),
                  IoError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("staged run: sequential calls, then the confidence graph; bit-identical for any "
          "thread count", "[posegraph][confidence]") {
  const auto s = small_scene(5, 600);
  auto clouds = std::make_shared<const std::vector<FrameCloud>>(s.clouds);
  std::vector<Pose> init;
  Rng rng(41);
  for (const auto& T : s.T) {
    Vec6 xi;
    for (int k = 0; k < 6; ++k) xi[k] = (k < 3 ? 0.01 : 0.2) * rng.normal();
    init.push_back(corrected_pose(T, xi));
  }
  StagedGraphConfig sc;
  sc.anneal.steps = 40;
  sc.anneal.per_call = 10;
  sc.confidence_start = 0.5;  // graphs after calls 2 and 3
  auto run = [&](int threads, std::vector<int>* graph_calls) {
    GeometricConfig base;
    base.threads = threads;
    ConfidenceGraphConfig gc;
    gc.min_matches = 10;
    gc.min_index_gap = 0;
    gc.compatibility_test = true;
    gc.kappa = -3.0;
    gc.reevaluate_every = 1;
    gc.threads = threads;
    std::vector<Pose> T = init;
    const auto r = run_staged_graph(clouds, base, sc, gc, standin_fourier_features({}), T, {},
                                    [&](const GraphEvaluation& e) {
                                      if (graph_calls) graph_calls->push_back(e.after_call);
                                    });
    CHECK(r.calls.size() == 4);
    return std::make_pair(T, r);
  };
  std::vector<int> calls;
  const auto [T1, r1] = run(1, &calls);
  const auto [T2, r2] = run(2, nullptr);
  CHECK(calls == std::vector<int>{2, 3});
  REQUIRE(r1.graphs.size() == 2);
  CHECK(r1.graphs[0].graph.edges.size() > 4);  // the non-adjacent pairs joined
  for (size_t k = 0; k < T1.size(); ++k) CHECK(T1[k].matrix() == T2[k].matrix());
  for (size_t k = 0; k < r1.graphs.size(); ++k)
    CHECK(confidence_graph_json(r1.graphs[k].graph).dump() ==
          confidence_graph_json(r2.graphs[k].graph).dump());
  // The poses moved, and the graph stage changed them compared with the sequential graph alone.
  sc.confidence = false;
  const auto [T3, r3] = run(1, nullptr);
  CHECK(r3.graphs.empty());
  double diff = 0;
  for (size_t k = 0; k < T1.size(); ++k)
    diff += (T1[k].translation() - T3[k].translation()).norm();
  CHECK(diff > 1e-6);
  // Bad schedule values are named.
  sc.confidence_start = 1.5;
  CHECK_THROWS_WITH(run(1, nullptr), Catch::Contains("confidence_start"));
}
