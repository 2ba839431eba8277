// What SG-NLF's hybrid field costs per pose-free training step (issue "SG-NLF, part 1", item 1):
// the same quick-preset step (1024 rays × 96 uniform samples, forward, loss, backward with the
// ray gradients the pose update needs, Adam) with GeoNLF's hash grid and with the hybrid
// [f_geo, λ·Ψ] at λ = 1 (Ψ evaluated forward and backward for dL/dx), and one spectral step of Ψ
// (1024 surface samples × 5 evaluations, loss and moments on the host, Adam) as the schedule
// runs it every `spectral.every` steps. Ratios of these are the cost of the hybrid field.
// And one step of SG-NLF's adversarial cross-frame consistency at the quick preset (
// render frame i on the 16 × 64 sub-sensor with the backward pass, reprojection into
// frame j's 66 × 103 image, one discriminator step, generator gradient, pose gradients), paid
// every `consistency.every` steps after the warm-up, against the quick pose-free step above.
#include <benchmark/benchmark.h>

#include "field/adam.hpp"
#include "support/bench_support.hpp"
#include "bench_dataset.hpp"
#include "pipeline/train/consistency_term.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "spectral/hybrid_encoder.hpp"
#include "pipeline/train/field_optimizer.hpp"
#include "spectral/surface.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

const Dataset& bench_dataset() { return bench::simulated_dataset("kitti360-low-a", 12); }

void BM_PoseFreeStep(benchmark::State& state, const char* method) {
  bench::add_device_context();
  const Scene scene = make_scene(bench_dataset());
  const TrainConfig c = resolve_config(method, "quick");
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
  model.init_params(1);
  if (model.hybrid()) model.set_fusion_weight(1.0f);
  FieldOptimizer optim(model, c);
  long step = 0;
  auto one = [&] {
    const RayBatch b = draw_ray_batch(scene, c, 1, step);
    model.forward_backward(b, 1, step++, true);
    optim.step(1e-2f);
    benchmark::DoNotOptimize(model.read_ray_grads());
  };
  one();
  for (auto _ : state) one();
  state.counters["samples/s"] = benchmark::Counter(
      double(c.schedule.rays_per_batch) * c.render.n_samples * double(state.iterations()),
      benchmark::Counter::kIsRate);
}

void BM_SpectralStep(benchmark::State& state) {
  bench::add_device_context();
  const TrainConfig c = resolve_config("sg-nlf-no-consistency", "quick");
  const Scene scene = make_scene(bench_dataset());
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
  model.init_params(1);
  OwnGroupStep group(model, 1, 0);  // Ψ's own step, as the spectral loss term takes it
  field::Adam adam(bench::runtime(), model.psi_params());
  const auto shape = spectral::make_shape(spectral::ShapeSpec::preset(spectral::ShapeKind::sphere));
  Rng rng(3, 1);
  auto batch = shape->sample(rng, size_t(c.spectral->batch));
  const auto step = [&] {
    const double l = group.spectral_gradient(batch);
    const OwnGroupStep::Group psi = group.psi();
    adam.begin_step();
    adam.update(psi.params, psi.grad, 0, psi.count, 1e-2f);
    return l;
  };
  step();
  for (auto _ : state) benchmark::DoNotOptimize(step());
}

void BM_ConsistencyStep(benchmark::State& state) {
  bench::add_device_context();
  const TrainConfig c = resolve_config("sg-nlf", "quick");
  const Scene scene = make_scene(bench_dataset());
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
  model.init_params(1);
  model.set_fusion_weight(1.0f);
  ConsistencyTerm term(bench::runtime(), scene, *c.consistency, c.schedule.rays_per_batch);
  ConsistencyPair p;
  p.i = 3, p.j = 4;
  p.T_init_i = scene.T_world_lidar[3], p.T_init_j = scene.T_world_lidar[4];
  long step = 0;
  const RayBatch no_batch;
  auto run = [&] {
    FieldPass field(model, no_batch, 1, step++);
    return term.run(field, p, true, true);
  };
  run();
  for (auto _ : state) benchmark::DoNotOptimize(run().l_con);
  state.counters["render_rays"] = term.render_sensor().height * term.render_sensor().width;
  state.counters["image_px"] = term.image_sensor().height * term.image_sensor().width;
}

}  // namespace

BENCHMARK_CAPTURE(BM_PoseFreeStep, geonlf_quick, "geonlf")
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK_CAPTURE(BM_PoseFreeStep, hybrid_quick, "sg-nlf-no-consistency")
    ->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_ConsistencyStep)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK(BM_SpectralStep)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
