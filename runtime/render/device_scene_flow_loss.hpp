// LiDAR4D's scene-flow losses on the device (device profile chamfer: device; kernels/render/
// chamfer.cl): render::scene_flow_loss times the supervision's weight on a frame's moving
// points and render::ground_flow_penalty on its ground points (render/scene_flow_loss.hpp), as
// pipeline::FlowSupervision combines them, from the flow on the device to dL/dflow on the device,
// every kernel enqueued and nothing read back. The value stays in kSlots floats on the device
// (the Chamfer terms of the frames k ± s, then the ground penalty) until read() is asked for it.
#pragma once
#include <vector>

#include "cl/runtime.hpp"
#include "render/device_chamfer.hpp"

namespace sgnlf::render {

// The frames around k, as FlowNeighbours: the points of frame k ± (s + 1) are the first
// n_next[s] / n_prev[s] points (n × 3) of next[s] / prev[s]; null or 0 points: no frame.
struct DeviceFlowNeighbours {
  const cl::Buffer* next[2] = {nullptr, nullptr};
  const cl::Buffer* prev[2] = {nullptr, nullptr};
  int n_next[2] = {0, 0}, n_prev[2] = {0, 0};
};

class DeviceSceneFlowLoss {
 public:
  // The value's slots: side · 2 + (s − 1) for the forward (side 0) and backward (side 1) flow
  // to k ± s, then the ground penalty's.
  static constexpr int kSlots = 5;
  static constexpr int kGroundSlot = 4;

  explicit DeviceSceneFlowLoss(cl::Runtime& rt);

  // x: the frame's m moving then g ground points ((m + g) × 3); flow: their flow ((m + g) × 6,
  // forward then backward). Writes d_flow ((m + g) × 6): weight · dL/dflow of
  // scene_flow_loss(moving, neighbours, steps) on the moving rows, ground_flow_penalty's
  // gradient (ground_weight) on the ground rows; the value into slots().
  void run(const cl::Buffer& x, int m, int g, const cl::Buffer& flow,
           const DeviceFlowNeighbours& neighbours, int steps, float weight, float ground_weight,
           cl::Buffer& d_flow);

  const cl::Buffer& slots() const { return slots_; }
  // weight · Σ Chamfer slots + the ground slot, in double (pipeline::FlowSupervision's value).
  static double value(const std::vector<float>& slots, double weight);
  // The same from one blocking read of slots().
  double read(double weight) const;

 private:
  cl::Runtime& rt_;
  DeviceChamfer chamfer_;
  cl::Kernel points_, finish_;
  cl::Buffer moved_, terms_, slots_;
  size_t cap_ = 0;
};

}  // namespace sgnlf::render
