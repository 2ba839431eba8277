// Rendering a trained field: the protocol's renderer (render_rays: every sample through the
// density MLP and the head) against the fast renderer (render_rays_fast: occupancy grid, early
// termination, the head where the weight matters) on the same rays, a block of a test frame of
// the shared trained LiDAR-NeRF quick field (bench_trained.hpp), chunk by chunk as
// `sgnlf render` does. Reports rays/s, the density and head rows per ray, and the MLPs' FLOPs
// as a fraction of the measured roofline (the hash grid's gathers are not counted: its share
// is in bench_field's gathers/s).
#include <benchmark/benchmark.h>

#include <chrono>

#include "bench_trained.hpp"
#include "field/mlp.hpp"
#include "pipeline/model/fast_renderer.hpp"

using namespace sgnlf;
using namespace sgnlf::pipeline;

namespace {

constexpr int kChunk = 2048, kChunks = 4;

void BM_RenderView(benchmark::State& state, bool fast) {
  bench::add_device_context();
  const Dataset& d = bench::bench_dataset();
  const Scene scene = make_scene(d);
  TrainConfig c = resolve_config("lidar-nerf", "quick");
  // Rendered as `sgnlf render` renders a run: the preset's evaluation sampling.
  if (c.render.eval_samples > 0) c.render.n_samples = c.render.eval_samples;
  if (c.render.eval_importance >= 0) c.render.n_importance = c.render.eval_importance;
  LidarNerfModel model(bench::runtime(), c, float(scene.norm.scale), kChunk);
  model.set_params(bench::trained_state().params);
  const render::FastRenderConfig fc;
  FastRenderer renderer(bench::runtime(), model, scene, fc, kChunk);
  const int frame = d.split.test.front();
  const render::OccupancyGrid& grid = renderer.grid(frame);
  const Pose T = normalize_pose(d.frames[size_t(frame)].T_world_lidar, scene.norm);
  // The middle rows of the frame, where most returns are.
  const size_t first = size_t(scene.sensor.width) * size_t(scene.sensor.height / 3);
  std::vector<std::vector<float>> o(kChunks), dir(kChunks);
  for (int k = 0; k < kChunks; ++k)
    image_rays(scene, T, first + size_t(k) * kChunk, first + size_t(k + 1) * kChunk, o[size_t(k)],
               dir[size_t(k)]);
  const int M = c.render.n_samples + c.render.n_importance;
  double density_rows = 0, head_rows = 0, secs = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < kChunks; ++k) {
      const auto out = fast ? model.render_rays_fast(o[size_t(k)], dir[size_t(k)], kChunk, grid, fc)
                            : model.render_rays(o[size_t(k)], dir[size_t(k)], kChunk);
      benchmark::DoNotOptimize(out.data());
      density_rows += fast ? double(model.fast_evaluated()) : double(kChunk) * M;
      head_rows += fast ? double(model.fast_head_rows()) : double(kChunk) * M;
    }
    secs += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  const double rays = double(kChunk) * kChunks * double(state.iterations());
  state.counters["rays/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  state.counters["density_rows/ray"] = density_rows / rays;
  state.counters["head_rows/ray"] = head_rows / rays;
  state.counters["grid_occupied"] = grid.occupied_fraction();
  // MLP FLOPs per iteration: density MLP on every density row, head on every head row.
  const auto& f = c.field;
  const field::MlpSpec dens = field::make_mlp_spec(f.grid.levels * f.grid.features, f.density_hidden,
                                                   1, 1 + f.geo_features, field::Activation::Relu);
  // The head's first layer also takes the direction encoding (once per ray: not counted).
  const field::MlpSpec head = field::make_mlp_spec(f.geo_features, f.head_hidden, f.head_layers,
                                                   2, field::Activation::Relu);
  const double per_iter = (density_rows * dens.macs_per_point() + head_rows * head.macs_per_point()) *
                          2.0 / double(state.iterations());
  bench::set_roofline_counters(state, secs, per_iter, 0.0);
}

}  // namespace

BENCHMARK_CAPTURE(BM_RenderView, protocol, false)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
BENCHMARK_CAPTURE(BM_RenderView, fast, true)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);
