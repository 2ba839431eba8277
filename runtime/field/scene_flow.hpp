// LiDAR4D's scene-flow field (method.md §2; LiDAR4D model/flow_field.py, the grid version): a
// 3D hash grid over x whose per-level features are B chunks at the time nodes j/(B − 1),
// interpolated at t with Lagrange polynomials (kernels/field/scene_flow.cl), then a bias-free
// ReLU MLP to 6 outputs: the forward flow (x at t → t + dt) and the backward flow (→ t − dt),
// displacements in the normalised box. (x, t) is the 4D input; t is not differentiated.
// LiDAR4D's sizes: 8 levels × 8 features, base 32, finest 8192, 2^18 entries, 4 time nodes,
// 3 layers of 64, output weights N(0, 0.001²) so the flow starts near zero.
// Layout of the module slice: the hash grid, then the MLP (runtime/field/mlp.hpp, bias rows
// present and zero).
#pragma once
#include <cstdint>
#include <string>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "field/hash_grid.hpp"
#include "field/scene_flow_config.hpp"
#include "field/mlp.hpp"

namespace sgnlf::field {

// The bias-free MLP (grid features / time_nodes → hidden → 6) of a configuration.
MlpSpec scene_flow_mlp_spec(const SceneFlowConfig& cfg);

class SceneFlow {
 public:
  SceneFlow(cl::Runtime& rt, const SceneFlowConfig& cfg);

  const SceneFlowConfig& config() const { return cfg_; }
  size_t n_params() const { return grid_.n_params() + mlp_.n_params(); }
  size_t mlp_offset() const { return grid_.n_params(); }  // within the module slice
  const HashGrid& grid() const { return grid_; }
  const Mlp& mlp() const { return mlp_; }

  // Grid ±1e-4 (instant-ngp), hidden layers Mlp's fan-in init, output weights N(0, std²).
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const;

  // flow (N × 6: forward then backward displacement) at x (N × 3) and times t (N).
  // Keeps what backward needs; x, t and flow must stay unchanged until then. Enqueued.
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, const cl::Buffer& t,
               int n, cl::Buffer& flow);
  // From d_flow (N × 6): overwrites grad[grad_offset, + n_params()); writes dL/dx (N × 3)
  // when d_x is given. Same x, t, flow as the preceding forward. Enqueued.
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, const cl::Buffer& t,
                int n, const cl::Buffer& flow, const cl::Buffer& d_flow, cl::Buffer& grad,
                size_t grad_offset, cl::Buffer* d_x = nullptr);

 private:
  cl::Runtime& rt_;
  SceneFlowConfig cfg_;
  HashGrid grid_;
  Mlp mlp_;
  MlpContext ctx_;
  cl::Kernel time_fwd_, time_bwd_;
  bool wide_ = false;  // the profile's ray_work_items > 1 when made: a work-item per output word
  cl::Buffer grid_out_, mlp_in_, d_mlp_in_, d_grid_out_;
  size_t capacity_ = 0;
  void ensure(int n);
};

}  // namespace sgnlf::field
