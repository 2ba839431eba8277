// One whole LiDAR-NeRF training step (sampling, coarse pass, importance sampling, field forward,
// volume rendering, loss, backward chain, Adam) on a small synthetic sequence, for the smoke and
// quick presets. Reports wall time per step (the step is enqueued whole and waited once) and
// samples/s = rays × (uniform + importance) / step time.
#include <benchmark/benchmark.h>

#include "support/bench_support.hpp"
#include "datasets/simulate.hpp"
#include "pipeline/model.hpp"
#include "pipeline/presets.hpp"
#include "pipeline/ray_batch.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

const Dataset& bench_dataset() {
  static const Dataset d = [] {
    SimOptions o;
    o.sequence = "kitti360-1538";
    o.frames = 14;
    o.threads = 1;
    return simulate(o).dataset;
  }();
  return d;
}

void BM_TrainStep(benchmark::State& state, const char* preset, bool reuse_coarse) {
  bench::add_device_context();
  const Scene scene = make_scene(bench_dataset());
  const TrainConfig c = resolve_config("lidar-nerf", preset);
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
  model.set_reuse_coarse_encodings(reuse_coarse);
  model.init_params(1);
  long step = 0;
  const RayBatch warm = draw_ray_batch(scene, c, 1, step);
  model.train_step(warm, 1, step++, 1e-2f);
  model.read_loss();
  for (auto _ : state) {
    const RayBatch b = draw_ray_batch(scene, c, 1, step);
    model.train_step(b, 1, step++, 1e-2f);
    benchmark::DoNotOptimize(model.read_loss());
  }
  const double samples = double(c.schedule.rays_per_batch) * (c.render.n_samples + c.render.n_importance);
  state.counters["samples/s"] =
      benchmark::Counter(samples * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(double(c.schedule.rays_per_batch) * double(state.iterations()),
                                                benchmark::Counter::kIsRate);
}

}  // namespace

// `quick_reencode`: the merged pass encodes the coarse samples again instead of reusing the
// coarse pass's encodings (the same result bit for bit; shows what the reuse saves).
BENCHMARK_CAPTURE(BM_TrainStep, smoke, "smoke", true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_TrainStep, quick, "quick", true)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStep, quick_reencode, "quick", false)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
