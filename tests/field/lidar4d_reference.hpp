// Host references and small configurations of LiDAR4D's scene-flow field and composite encoder
// (runtime/field/scene_flow.hpp, lidar4d_encoder.hpp), for tests only: the modules' own host
// references (reference.hpp, reference_4d.hpp) composed in the order method.md §2 reads.
#pragma once
#include <vector>

#include "field/lidar4d_encoder.hpp"
#include "field/scene_flow.hpp"

namespace sgnlf::test::ref {

// out[i, l·G + g] = Σ_j ℓ_j(t_i) · in[i, l·F + j·G + g] and its transpose (kernels/field/
// scene_flow.cl), in double.
std::vector<float> lagrange_fwd(int levels, int features, int nodes, const std::vector<float>& in,
                                const std::vector<float>& t);
std::vector<float> lagrange_bwd(int levels, int features, int nodes,
                                const std::vector<float>& d_out, const std::vector<float>& t);

// The flow (N × 6) of `slice` (the module slice); with d_flow, fills grad (module slice) and
// d_x (N × 3).
std::vector<float> scene_flow_fwd(const field::SceneFlowConfig& cfg,
                                  const std::vector<float>& slice,
                                  const std::vector<float>& x, const std::vector<float>& t);
void scene_flow_bwd(const field::SceneFlowConfig& cfg, const std::vector<float>& slice,
                    const std::vector<float>& x, const std::vector<float>& t,
                    const std::vector<float>& d_flow, std::vector<float>& grad,
                    std::vector<float>& d_x);

// The encoder's time state, as set_time() takes it.
struct TimeState {
  float t = 0.5f, dt = 0.25f;
  bool has_prev = true, has_next = true;
};
// The encoding (N × width) of x from the encoder's slice, every part from its own reference.
std::vector<float> lidar4d_fwd(const field::Lidar4DEncoderConfig& cfg,
                               const field::Lidar4DParamOffsets& off,
                               const std::vector<float>& slice, const std::vector<float>& x,
                               const TimeState& ts);

// Small shapes of every part (a few thousand parameters), for references and finite
// differences; flow_std sets the flow's output initialisation (large enough to move points).
field::Lidar4DEncoderConfig small_lidar4d_config(float flow_std = 0.05f);

}  // namespace sgnlf::test::ref
