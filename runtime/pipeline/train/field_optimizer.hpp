// The field's optimiser, composed by the training step (step_policy.hpp) beside the model:
// Adam (field::Adam, the config's optim.adam) over the model's flat parameter buffer, one launch
// per parameter group at the step's learning rate times the group's scale
// (LidarNerfModel::trainable()). Its moments and step count are checkpointed beside the
// parameters (trainer.cpp: "adam_m", "adam_v", the checkpoint's step).
#pragma once
#include <cstdint>
#include <vector>

#include "field/adam.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/model/model.hpp"

namespace sgnlf::pipeline {

struct OptimizerState {
  std::vector<float> m, v;
  int64_t step = 0;
};

class FieldOptimizer {
 public:
  // Zero moments for `model`'s parameters; the settings are c.optim.adam.
  FieldOptimizer(LidarNerfModel& model, const TrainConfig& c);
  // One Adam step of every parameter group from the gradient of the model's last
  // forward_backward (lr 0: the moments still take the gradient, the parameters stay: GeoNLF's
  // test frames). Enqueued, no wait.
  void step(float lr);
  // Zero moments and step count (blocking).
  void reset() { adam_.reset(); }
  // Host copies for checkpoints; set_state checks the sizes (IoError naming both).
  OptimizerState state() const;
  void set_state(const OptimizerState& s);
  const field::AdamConfig& config() const { return adam_.config(); }
  int64_t steps() const { return adam_.step(); }

 private:
  LidarNerfModel& model_;
  field::Adam adam_;
};

}  // namespace sgnlf::pipeline
