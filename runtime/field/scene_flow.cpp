// SceneFlow host code: configuration checks, initialisation and the enqueueing of the hash
// grid, the Lagrange time interpolation (kernels/field/scene_flow.cl) and the bias-free MLP.
#include "field/scene_flow.hpp"

#include <cmath>

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::field {

MlpSpec scene_flow_mlp_spec(const SceneFlowConfig& cfg) {
  MlpSpec s = make_mlp_spec(cfg.levels * cfg.features / cfg.time_nodes, cfg.hidden_width,
                            cfg.hidden_layers, 6,
                            Activation::Relu);
  s.bias = false;
  return s;
}

SceneFlow::SceneFlow(cl::Runtime& rt, const SceneFlowConfig& cfg)
    : rt_(rt), cfg_(cfg), grid_(rt, cfg.grid_config()), mlp_(rt, scene_flow_mlp_spec(cfg)) {
  const std::string opt = "-DLEVELS=" + std::to_string(cfg_.levels) +
                          " -DFEATURES=" + std::to_string(cfg_.features) +
                          " -DBASIS=" + std::to_string(cfg_.time_nodes);
  // Under the gpu profile (ray_work_items > 1) a work-item per output word: scene_flow.cl.
  wide_ = rt_.device_profile().ray_work_items > 1;
  time_fwd_ = rt_.kernel("field/scene_flow.cl",
                         wide_ ? "field_scene_flow_time_fwd_wide" : "field_scene_flow_time_fwd", opt);
  time_bwd_ = rt_.kernel("field/scene_flow.cl",
                         wide_ ? "field_scene_flow_time_bwd_wide" : "field_scene_flow_time_bwd", opt);
}

void SceneFlow::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) const {
  if (offset + n_params() > host_params.size())
    throw Error("SceneFlow::init_params: slice exceeds buffer of " +
                std::to_string(host_params.size()) + " floats");
  grid_.init_params(host_params, offset, seed);
  const size_t m = offset + mlp_offset();
  mlp_.init_params(host_params, m, seed ^ 0x5346u);
  // Output layer: N(0, std²) on the real weights (padding columns and bias stay zero).
  Rng rng(seed, 0x53464fu);
  const int last = int(mlp_.spec().layers.size()) - 1;
  const int n_in = last == 0 ? mlp_.spec().n_in : mlp_.spec().layers[size_t(last) - 1].width;
  const int out_pad = Mlp::pad16(6);
  float* w = host_params.data() + m + mlp_.layer_offset(last);
  for (int i = 0; i < n_in; ++i)
    for (int o = 0; o < 6; ++o)
      w[size_t(i) * out_pad + o] = float(cfg_.out_init_std * rng.normal());
}

void SceneFlow::ensure(int n) {
  if (capacity_ >= size_t(n)) return;
  const size_t lf = size_t(cfg_.levels) * cfg_.features, in = lf / size_t(cfg_.time_nodes);
  grid_out_ = cl::Buffer(rt_, size_t(n) * lf * 4);
  d_grid_out_ = cl::Buffer(rt_, size_t(n) * lf * 4);
  mlp_in_ = cl::Buffer(rt_, size_t(n) * in * 4);
  d_mlp_in_ = cl::Buffer(rt_, size_t(n) * in * 4);
  capacity_ = size_t(n);
}

void SceneFlow::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                        const cl::Buffer& t, int n, cl::Buffer& flow) {
  if (n < 0) throw Error("SceneFlow: negative point count " + std::to_string(n));
  if (t.bytes() < size_t(n) * 4 || flow.bytes() < size_t(n) * 24)
    throw Error("SceneFlow::forward: t or flow buffer too small for " + std::to_string(n) +
                " points");
  if (n == 0) return;
  ensure(n);
  grid_.forward(params, offset, x, n, grid_out_);
  time_fwd_.set_args(n, t, grid_out_, mlp_in_);
  // The trace's element count: the grid features read (grid_out_ may be sized for more points).
  const size_t lf = size_t(cfg_.levels) * size_t(cfg_.features);
  cl::launch_1d(time_fwd_, wide_ ? size_t(n) * (lf / size_t(cfg_.time_nodes)) : size_t(n),
                size_t(n) * lf);
  mlp_.forward(params, offset + mlp_offset(), mlp_in_, n, flow, ctx_);
}

void SceneFlow::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x,
                         const cl::Buffer& t, int n, const cl::Buffer& flow,
                         const cl::Buffer& d_flow, cl::Buffer& grad, size_t grad_offset,
                         cl::Buffer* d_x) {
  if (n <= 0 || capacity_ < size_t(n) || ctx_.n != n)
    throw Error("SceneFlow::backward: no forward of " + std::to_string(n) + " points before");
  mlp_.backward(params, offset + mlp_offset(), ctx_, flow, d_flow, grad,
                grad_offset + mlp_offset(), &d_mlp_in_);
  time_bwd_.set_args(n, t, d_mlp_in_, d_grid_out_);
  const size_t lf = size_t(cfg_.levels) * size_t(cfg_.features);
  cl::launch_1d(time_bwd_, wide_ ? size_t(n) * lf : size_t(n), size_t(n) * lf);
  grid_.backward(params, offset, x, n, d_grid_out_, grad, grad_offset, d_x);
}

}  // namespace sgnlf::field
