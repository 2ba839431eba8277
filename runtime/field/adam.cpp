// Adam host launcher.
#include "field/adam.hpp"

#include <cmath>
#include <string>

#include "cl/launch.hpp"
#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::field {

Adam::Adam(cl::Runtime& rt, size_t n_params, const AdamConfig& cfg)
    : rt_(rt), cfg_(cfg), n_params_(n_params) {
  cfg_.validate();
  if (n_params == 0) throw Error("Adam: zero parameters");
  m_ = cl::Buffer(rt_, n_params * sizeof(float));
  v_ = cl::Buffer(rt_, n_params * sizeof(float));
  reset();
  kernel_ = rt_.kernel("optim/adam.cl", "optim_adam_step");
}

void Adam::reset() {
  m_.fill_zero();
  v_.fill_zero();
  step_ = 0;
}

void Adam::update(cl::Buffer& params, const cl::Buffer& grad, size_t offset, size_t count,
                  float lr) {
  if (step_ <= 0) throw Error("Adam::update: call begin_step() first");
  if (offset + count > n_params_ || params.bytes() < (offset + count) * 4 ||
      grad.bytes() < (offset + count) * 4)
    throw Error("Adam::update: group [" + std::to_string(offset) + ", +" +
                std::to_string(count) + ") outside the buffers of " + std::to_string(n_params_));
  if (count == 0) return;
  const double t = double(step_);
  const float c1 = float(1.0 / (1.0 - std::pow(double(cfg_.beta1), t)));
  const float c2 = float(1.0 / std::sqrt(1.0 - std::pow(double(cfg_.beta2), t)));
  kernel_.set_args(uint32_t(offset), uint32_t(count), lr, cfg_.beta1, cfg_.beta2, cfg_.eps, c1, c2,
                   cfg_.weight_decay, params, grad, m_, v_);
  cl::launch_1d(kernel_, count);
}

}  // namespace sgnlf::field
