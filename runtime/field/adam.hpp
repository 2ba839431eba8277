// Adam over one flat parameter buffer (method.md §0 "Optimiser"): one kernel
// (kernels/optim/adam.cl) launched per parameter group (offset, count, lr), moments m and v
// owned here with the same layout as the parameters, PyTorch's bias correction.
#pragma once
#include <cstdint>

#include "cl/runtime.hpp"
#include "field/adam_config.hpp"

namespace sgnlf::field {

class Adam {
 public:
  // Moments for a flat buffer of n_params floats, zero-initialised.
  Adam(cl::Runtime& rt, size_t n_params, const AdamConfig& cfg = {});

  const AdamConfig& config() const { return cfg_; }
  // Starts a new step: increments the step counter t used for bias correction.
  void begin_step() { ++step_; }
  int64_t step() const { return step_; }
  // Updates params[offset, offset + count) from grad with learning rate lr (lr = 0: moments
  // still update, parameters stay). Enqueued, no wait. Requires begin_step() first.
  void update(cl::Buffer& params, const cl::Buffer& grad, size_t offset, size_t count, float lr);
  void reset();  // zero moments and step counter (blocking)

  cl::Buffer& m() { return m_; }
  cl::Buffer& v() { return v_; }
  const cl::Buffer& m() const { return m_; }
  const cl::Buffer& v() const { return v_; }

 private:
  cl::Runtime& rt_;
  AdamConfig cfg_;
  size_t n_params_;
  int64_t step_ = 0;
  cl::Buffer m_, v_;
  cl::Kernel kernel_;
};

}  // namespace sgnlf::field
