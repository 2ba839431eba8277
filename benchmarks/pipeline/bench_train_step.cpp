// One whole LiDAR-NeRF training step (sampling, coarse pass, importance sampling, field forward,
// volume rendering, loss, backward chain, Adam) on a small synthetic sequence, for the smoke and
// quick presets. Reports wall time per step (the step is enqueued whole and waited once) and
// samples/s = rays × (uniform + importance) / step time.
// The `trained` pair measures early ray termination where it matters, on a field trained for
// 1000 steps first (untrained fields are translucent and terminate nothing): the same state is
// stepped with and without `render.stop_transmittance`; live/sample reports the fraction of
// merged samples the field evaluated (coarse/uniform, head/live, evaluated/s, free/live: see
// below).
#include <benchmark/benchmark.h>

#include <algorithm>

#include "support/bench_support.hpp"
#include "bench_dataset.hpp"
#include "bench_trained.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/ray_batch.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

using bench::bench_dataset;
using bench::kWarmSteps;
using bench::trained_state;

// stop_transmittance < 0 keeps the preset's.
void BM_TrainStep(benchmark::State& state, const char* preset, bool reuse_coarse,
                  float stop_transmittance = -1.0f) {
  bench::add_device_context();
  const Scene scene = make_scene(bench_dataset());
  TrainConfig c = resolve_config("lidar-nerf", preset);
  if (stop_transmittance >= 0.0f) c.render.stop_transmittance = stop_transmittance;
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
  model.set_reuse_coarse_encodings(reuse_coarse);
  model.init_params(1);
  FieldOptimizer optim(model, c);
  long step = 0;
  const RayBatch warm = draw_ray_batch(scene, c, 1, step);
  model.forward_backward(warm, 1, step++);
  optim.step(1e-2f);
  model.read_losses();
  for (auto _ : state) {
    const RayBatch b = draw_ray_batch(scene, c, 1, step);
    model.forward_backward(b, 1, step++);
    optim.step(1e-2f);
    benchmark::DoNotOptimize(model.read_losses());
  }
  const double samples = double(c.schedule.rays_per_batch) * (c.render.n_samples + c.render.n_importance);
  state.counters["samples/s"] =
      benchmark::Counter(samples * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(double(c.schedule.rays_per_batch) * double(state.iterations()),
                                                benchmark::Counter::kIsRate);
}

// Uniform samples of a batch that lie in known free space: on each ray with a return, the
// stratified bins that end more than one cell of a 128³ grid over the normalised box [-1, 1]³
// in front of the measured range. What an occupancy structure could skip at best (
// rays without a return are not counted, the importance samples sit at the surface): as a
// share of the live samples (free/live), it bounds the saving of the training pass.
long free_space_samples(const RayBatch& b, const TrainConfig& c, float scene_scale) {
  const double near = c.render.near_m * scene_scale, far = c.render.far_m * scene_scale;
  const double bin = (far - near) / c.render.n_samples, cell = 2.0 / 128.0;
  long n = 0;
  for (int r = 0; r < b.n_rays; ++r) {
    if (b.label[size_t(r)] < 0.5f) continue;
    const double front = double(b.range[size_t(r)]) - cell - near;  // bins ending before this
    if (front > 0.0) n += std::min<long>(long(front / bin), c.render.n_samples);
  }
  return n;
}

void BM_TrainStepTrained(benchmark::State& state, float stop_transmittance, int coarse_waves = 1,
                         float head_threshold = 0.0f) {
  bench::add_device_context();
  const Scene scene = make_scene(bench_dataset());
  TrainConfig c = resolve_config("lidar-nerf", "quick");
  c.render.stop_transmittance = stop_transmittance;
  c.render.coarse_waves = coarse_waves;
  c.render.head_weight_threshold = head_threshold;
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
  model.set_params(trained_state().params);
  FieldOptimizer optim(model, c);
  optim.set_state(trained_state().adam);
  long step = kWarmSteps;
  double live = 0.0, coarse = 0.0, head = 0.0, evals = 0.0, free = 0.0, dropped = 0.0;
  const double samples = double(c.schedule.rays_per_batch) * (c.render.n_samples + c.render.n_importance);
  for (auto _ : state) {
    const RayBatch b = draw_ray_batch(scene, c, 1, step);
    model.forward_backward(b, 1, step++);
    optim.step(1e-3f);
    benchmark::DoNotOptimize(model.read_losses());
    live += double(model.live_samples()) / samples;
    evals += double(model.live_samples() + model.coarse_evaluated());
    coarse += double(model.coarse_evaluated()) / double(c.schedule.rays_per_batch * c.render.n_samples);
    head += head_threshold > 0.0f ? double(model.head_rows()) / double(std::max(model.live_samples(), 1L)) : 1.0;
    const double live_n = double(std::max(model.live_samples(), 1L));
    free += double(free_space_samples(b, c, float(scene.norm.scale))) / live_n;
    const int merged = c.render.n_samples + c.render.n_importance;
    const std::vector<int> per_ray = stop_transmittance > 0.0f
                                         ? model.live_counts()
                                         : std::vector<int>(size_t(b.n_rays), merged);
    long no_return = 0;
    for (int r = 0; r < b.n_rays; ++r)
      if (b.label[size_t(r)] < 0.5f) no_return += per_ray[size_t(r)];
    dropped += double(no_return) / live_n;
  }
  state.counters["samples/s"] =
      benchmark::Counter(samples * double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["live/sample"] = live / double(std::max<int64_t>(state.iterations(), 1));
  state.counters["coarse/uniform"] = coarse / double(std::max<int64_t>(state.iterations(), 1));
  state.counters["head/live"] = head / double(std::max<int64_t>(state.iterations(), 1));
  state.counters["free/live"] = free / double(std::max<int64_t>(state.iterations(), 1));
  // The live samples of rays without a measured return (sky, and the sensor's drops).
  state.counters["noreturn/live"] = dropped / double(std::max<int64_t>(state.iterations(), 1));
  // Field evaluations actually made (density-pass samples + live samples of the training
  // pass), against samples/s, the uniform-equivalent rate (rays × (uniform + importance)).
  state.counters["evaluated/s"] = benchmark::Counter(evals, benchmark::Counter::kIsRate);
}

}  // namespace

// `quick_reencode`: the merged pass encodes the coarse samples again instead of reusing the
// coarse pass's encodings (the same result bit for bit; shows what the reuse saves).
BENCHMARK_CAPTURE(BM_TrainStep, smoke, "smoke", true)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_TrainStep, quick, "quick", true)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
// `quick_exact`: without early termination; at initialisation nothing terminates, so the
// difference to `quick` is what the compaction costs when it saves nothing.
BENCHMARK_CAPTURE(BM_TrainStep, quick_exact, "quick", true, 0.0f)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStep, quick_reencode, "quick", false)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_exact, 0.0f)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_terminate, 1e-4f)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
// Early termination of the coarse pass too (render.coarse_waves); coarse/uniform is
// the fraction of the uniform samples the coarse pass evaluated.
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_waves4, 1e-4f, 4)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_waves8, 1e-4f, 8)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
// The LiDAR head only on the band of samples with weight > 1e-4 (render.head_weight_threshold);
// head/live is the fraction of the live samples the head ran on. Then both options.
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_band, 1e-4f, 1, 1e-4f)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_waves4_band, 1e-4f, 4, 1e-4f)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
BENCHMARK_CAPTURE(BM_TrainStepTrained, quick_trained_waves8_band, 1e-4f, 8, 1e-4f)
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(5.0);
