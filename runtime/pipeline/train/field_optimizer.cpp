// The field's optimiser (field_optimizer.hpp).
#include "pipeline/train/field_optimizer.hpp"

#include <string>

#include "core/error.hpp"

namespace sgnlf::pipeline {

FieldOptimizer::FieldOptimizer(LidarNerfModel& model, const TrainConfig& c)
    : model_(model), adam_(model.runtime(), model.n_params(), c.optim.adam) {}

void FieldOptimizer::step(float lr) {
  LidarNerfModel::Trainable t = model_.trainable();
  adam_.begin_step();
  for (const auto& g : t.groups)  // a scale of 1 gives lr's own bits
    adam_.update(t.params, t.grad, g.offset, g.count, float(double(lr) * g.lr_scale));
}

OptimizerState FieldOptimizer::state() const {
  const size_t n = model_.n_params();
  return {adam_.m().read_vec<float>(n), adam_.v().read_vec<float>(n), adam_.step()};
}

void FieldOptimizer::set_state(const OptimizerState& s) {
  const size_t n = model_.n_params();
  if (s.m.size() != n || s.v.size() != n)
    throw IoError("optimizer state: " + std::to_string(s.m.size()) + " and " +
                  std::to_string(s.v.size()) + " moments, the model has " + std::to_string(n) +
                  " parameters");
  adam_.reset();
  adam_.m().write_vec(s.m);
  adam_.v().write_vec(s.v);
  for (int64_t i = 0; i < s.step; ++i) adam_.begin_step();  // Adam exposes no setter
}

}  // namespace sgnlf::pipeline
