// The trained field the pipeline benchmarks share: the LiDAR-NeRF quick preset trained for
// kWarmSteps on 14 frames of kitti360-1538 (untrained fields are translucent: early termination
// and the fast renderer's grid have nothing to cut), once per process.
#pragma once
#include "bench_dataset.hpp"
#include "pipeline/config/presets.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/ray_batch.hpp"
#include "pipeline/train/field_optimizer.hpp"
#include "support/bench_support.hpp"

namespace sgnlf::bench {

inline const Dataset& bench_dataset() { return simulated_dataset("kitti360-1538", 14); }

constexpr long kWarmSteps = 1000;

// The field's parameters and its optimiser's state after the warm steps.
struct TrainedField {
  std::vector<float> params;
  pipeline::OptimizerState adam;
};

inline const TrainedField& trained_state() {
  static const TrainedField st = [] {
    using namespace pipeline;
    const Scene scene = make_scene(bench_dataset());
    const TrainConfig c = resolve_config("lidar-nerf", "quick");
    LidarNerfModel model(runtime(), c, float(scene.norm.scale), c.schedule.rays_per_batch);
    FieldOptimizer optim(model, c);
    model.init_params(1);
    for (long step = 0; step < kWarmSteps; ++step) {
      model.forward_backward(draw_ray_batch(scene, c, 1, step), 1, step);
      optim.step(float(c.optim.lr_at(step, c.schedule.iterations)));
    }
    model.read_losses();
    return TrainedField{model.params(), optim.state()};
  }();
  return st;
}

}  // namespace sgnlf::bench
