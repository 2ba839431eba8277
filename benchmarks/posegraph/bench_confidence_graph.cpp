// Cost of building SG-NLF's confidence-aware pose graph (method.md §4.2) and how it grows with
// the number of frames: simulated kitti360-low-a drives (an open street at 2 Hz, ≈ 5–10 m
// between frames) of 36, 100 and 300 frames, one ray per pixel of a 66 × 360 grid, 4000 match
// points per frame, graph built under the ground-truth poses with the STAND-IN features
// (random Fourier features of x_world, host; the pipeline's f_hyb runs on the device instead).
// Candidates pruned by sensor distance (40 m, the default) against no pruning (every pair);
// min_index_gap 0 here (every pair within the distance is matched, not only loop closures: the
// larger workload).
// Args: frames, pruned (1) or all pairs (0), threads. Wall-clock time, host only.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "datasets/protocol.hpp"
#include "datasets/simulate.hpp"
#include "posegraph/confidence_graph.hpp"
#include "posegraph/standin_features.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

struct Drive {
  std::vector<FrameCloud> clouds;
  std::vector<Pose> T;
};

const Drive& drive(int frames) {
  static std::map<int, std::unique_ptr<Drive>> cache;
  auto& d = cache[frames];
  if (!d) {
    SimOptions o;
    o.sequence = "kitti360-low-a";
    o.frames = frames;
    o.width = 360;
    o.lidar.beams = "grid";
    o.threads = 2;
    const Dataset ds = simulate_dataset(o);
    std::vector<std::vector<PointXYZI>> scans;
    for (const auto& f : ds.frames) scans.push_back(f.points);
    d = std::make_unique<Drive>(Drive{make_frame_clouds(scans, 4000, 1), gt_poses(ds)});
  }
  return *d;
}

void BM_ConfidenceGraph(benchmark::State& state) {
  const Drive& d = drive(int(state.range(0)));
  ConfidenceGraphConfig c;
  c.min_index_gap = 0;
  if (state.range(1) == 0) c.candidate_distance_m = 1e6;
  c.threads = int(state.range(2));
  const FeatureProvider f = standin_fourier_features({});
  ConfidenceGraph g;
  for (auto _ : state) {
    g = build_confidence_graph(d.clouds, d.T, f, c);
    benchmark::DoNotOptimize(g.edges.data());
  }
  size_t matches = 0;
  for (const auto& p : g.pairs) matches += p.matches;
  state.counters["frames"] = double(d.clouds.size());
  state.counters["candidates"] = double(g.pairs.size());
  state.counters["candidates_per_frame"] = double(g.pairs.size()) / double(d.clouds.size());
  state.counters["non_adjacent_kept"] = double(g.non_adjacent_edges());
  state.counters["fine_matches"] = double(matches);
  state.counters["ms_per_frame"] = benchmark::Counter(
      double(d.clouds.size()) * 1e-3, benchmark::Counter::kIsIterationInvariantRate |
                                          benchmark::Counter::kInvert);
}

// The stand-in features alone (4000 points of one frame): the part the device replaces.
void BM_StandinFeatures(benchmark::State& state) {
  const Drive& d = drive(36);
  const FeatureProvider f = standin_fourier_features({});
  std::vector<Eigen::Vector3f> x(d.clouds[0].points.begin(), d.clouds[0].points.end());
  for (auto _ : state) benchmark::DoNotOptimize(unit_features(f, x).data());
  state.counters["points"] = double(x.size());
  state.counters["dim"] = f.dim;
}

}  // namespace

BENCHMARK(BM_ConfidenceGraph)
    ->ArgNames({"frames", "pruned", "threads"})
    ->Args({36, 1, 1})
    ->Args({100, 1, 1})
    ->Args({300, 1, 1})
    ->Args({36, 0, 1})
    ->Args({100, 0, 1})
    ->Args({300, 1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_StandinFeatures)->Unit(benchmark::kMillisecond);
