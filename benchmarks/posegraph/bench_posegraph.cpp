// Cost of one GeoNLF geometric-optimiser call (method.md §3) as the pipeline makes it before an
// epoch: 36 frames of simulated kitti360-low-a (one ray per pixel of the 66 × 1030 grid),
// 12 000 or 4 000 points per frame, edges (i, i+1) and (i, i+2), 10 pose-only Adam steps (plus
// the final loss evaluation) from the protocol's noisy init. Wall-clock time, host only.
// Args: points per frame, threads.
#include <benchmark/benchmark.h>

#include "datasets/protocol.hpp"
#include "datasets/simulate.hpp"
#include "posegraph/geometric_optimizer.hpp"

using namespace sgnlf;
using namespace sgnlf::posegraph;

namespace {

const Dataset& sequence() {
  static const Dataset d = [] {
    SimOptions o;
    o.sequence = "kitti360-low-a";
    o.frames = 36;
    o.lidar.beams = "grid";
    o.threads = 2;
    return simulate_dataset(o);
  }();
  return d;
}

void BM_GeometricRun(benchmark::State& state) {
  GeometricConfig cfg;
  cfg.points_per_frame = size_t(state.range(0));
  cfg.threads = int(state.range(1));
  cfg.steps = 10;
  std::vector<std::vector<PointXYZI>> scans;
  for (const auto& f : sequence().frames) scans.push_back(f.points);
  const auto opt = GeometricOptimizer::from_scans(scans, cfg);
  const auto init = perturb_poses(gt_poses(sequence()), 1, 0.151, 2.0);
  GeometricResult r;
  for (auto _ : state) {
    auto T = init;
    r = opt.run(T, 0.5);
    benchmark::DoNotOptimize(T.data());
  }
  const double edges = double(sequential_edges(int(scans.size()), cfg.edge_offsets).size());
  state.counters["frames"] = double(scans.size());
  state.counters["edges"] = edges;
  // Per loss evaluation (steps + 1 per call): nearest-neighbour queries of both directions.
  state.counters["queries_per_eval"] = 2.0 * edges * double(cfg.points_per_frame);
  state.counters["evals_per_call"] = double(cfg.steps + 1);  // time per step ≈ Time / 11
  state.counters["loss_before"] = r.loss_before;
  state.counters["loss_after"] = r.loss_after;
}

}  // namespace

BENCHMARK(BM_GeometricRun)
    ->ArgNames({"points", "threads"})
    ->Args({12000, 1})
    ->Args({12000, 2})
    ->Args({4000, 1})
    ->Args({4000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
