// LiDAR4D's 4D hybrid encoding as a field::Encoder (method.md §2): composes the K-Planes planes
// (kplanes.hpp), the static 3D hash grid (hash_grid.hpp, lidar4d_static_hash_config()), the
// time-sliced hash grids (time_hash_grid.hpp) and the scene-flow field (scene_flow.hpp). A row
// of the output is
//   [ static planes (S·F) | static hash (L·F) | dynamic block: time planes (S·F) | time hash ],
// the dynamic block blended with the flowed neighbours (kernels/field/flow_blend.cl):
//   0.5·f(x, t) + 0.25·(f(x + flow_fwd, t + dt) + f(x + flow_bwd, t − dt)),
// f the dynamic features, flow = SceneFlow(x, t), dt one frame step; at the first (last) frame
// the missing neighbour's 0.25 goes to f(x, t), as LiDAR4D reuses the point's own features.
// Time: the frame of the batch is state, set between steps with set_frame() (LiDAR4D trains
// on rays of one frame per step, and the boundary rule is per frame), so the Encoder interface
// and every existing encoder stay as they are.
// Deviations from LiDAR4D (model/lidar4d.py): its columns are ordered [planes_s, planes_d,
// hash_s, hash_d]; here static then dynamic (a fixed permutation of the density MLP's inputs,
// which keeps the blended block contiguous). Its neighbour times are (k ± 1)/frames while its
// frame times are k/(frames − 1); here both are frame_time(), dt = 1/(frames − 1). It stops the
// gradient of the neighbours' hash features (torch.no_grad); here both neighbour encodings
// (planes and hash) pass gradients to their parameters and through x + flow to the flow field.
// Parameters in the model's slice: planes, static hash, time hash, flow field, in this order.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "field/encoder.hpp"
#include "field/hash_grid.hpp"
#include "field/kplanes.hpp"
#include "field/lidar4d_encoder_config.hpp"
#include "field/scene_flow.hpp"
#include "field/time_hash_grid.hpp"

namespace sgnlf::field {

// Where each module's parameters start within the encoder's slice. LiDAR4D's learning rates
// (model/lidar4d.py get_params): [planes, flow) are encodings (lr, 1e-2), [flow, end) the flow
// field, grid and MLP alike (0.1·lr, 1e-3, as the density MLP and the heads).
struct Lidar4DParamOffsets {
  size_t planes = 0, static_hash = 0, time_hash = 0, flow = 0, end = 0;
};

class Lidar4DEncoder : public Encoder {
 public:
  Lidar4DEncoder(cl::Runtime& rt, const Lidar4DEncoderConfig& cfg);

  // The frame of the following forward/backward passes: t = frame_time(frame, first, frames);
  // neighbours exist inside the sequence only.
  void set_frame(int frame, int first, int frames);
  // The same by value (tests, interpolated times): has_prev / has_next say which neighbours
  // t − dt / t + dt blend in.
  void set_time(float t, float dt, bool has_prev, bool has_next);
  float time() const { return t_; }

  int width() const override { return static_width() + dynamic_width(); }
  std::vector<int> parts() const override { return {static_width(), dynamic_width()}; }
  int static_width() const { return planes_.n_output(PlaneGroups::Static) + shash_.n_output(); }
  int dynamic_width() const { return planes_.n_output(PlaneGroups::Dynamic) + thash_.n_output(); }
  size_t n_params() const override { return off_.end; }
  const Lidar4DParamOffsets& offsets() const { return off_; }
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) override;
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
               cl::Buffer& enc) override;
  // Also the flow field's parameters (through x ± flow); d_x sums every path, flow included.
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                cl::Buffer* d_x) override;
  // No coarse-to-fine mask (LiDAR4D uses ground-truth poses): levels() = 0, and only an empty
  // weight list is accepted.
  int levels() const override { return 0; }
  void set_level_weights(const std::vector<float>& w) override;

  KPlanes& planes() { return planes_; }
  HashGrid& static_hash() { return shash_; }
  TimeHashGrid& time_hash() { return thash_; }
  SceneFlow& flow() { return flow_; }
  // The flow (N × 6) of the last forward (valid when a neighbour was blended in).
  const cl::Buffer& last_flow() const { return flow_out_; }

 private:
  cl::Runtime& rt_;
  Lidar4DEncoderConfig cfg_;
  KPlanes planes_;
  HashGrid shash_;
  TimeHashGrid thash_;
  SceneFlow flow_;
  Lidar4DParamOffsets off_;
  float t_ = 0.0f, dt_ = 0.0f;
  bool has_prev_ = false, has_next_ = false;
  cl::Kernel fill_, offset_, blend_fwd_, blend_bwd_, cols_get_, cols_set_, pack_, acc_;
  cl::Buffer t0_, t1_, t2_, flow_out_, x1_, x2_, hs_, nb1_, nb2_;
  cl::Buffer d_hs_, d_own_, d_nb1_, d_nb2_, dx1_, dx2_, dx_tmp_, d_flow_;
  size_t capacity_ = 0;
  int last_n_ = -1;
  bool uses_flow() const { return cfg_.blend && (has_prev_ || has_next_); }
  // The neighbouring frames' times the flowed points are encoded at.
  float next_time() const { return std::min(1.0f, t_ + dt_); }
  float prev_time() const { return std::max(0.0f, t_ - dt_); }
  void weights(float& w0, float& w1, float& w2) const;
  void ensure(int n);
  void fill(cl::Buffer& b, size_t offset, int n, float v);
  void add(const cl::Buffer& src, cl::Buffer& dst, int n);
};

}  // namespace sgnlf::field
