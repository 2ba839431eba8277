// DeviceSceneFlowLoss: the flow supervision's launches of kernels/render/chamfer.cl.
#include "render/device_scene_flow_loss.hpp"

#include <algorithm>

#include "render/launch.hpp"

namespace sgnlf::render {

DeviceSceneFlowLoss::DeviceSceneFlowLoss(cl::Runtime& rt)
    : rt_(rt),
      chamfer_(rt),
      points_(rt.kernel("render/chamfer.cl", "render_chamfer_flow_points",
                         chamfer_program_options())),
      finish_(rt.kernel("render/chamfer.cl", "render_chamfer_flow_finish",
                         chamfer_program_options())),
      slots_(rt, kSlots * sizeof(float)) {
  slots_.fill_zero();
}

void DeviceSceneFlowLoss::run(const cl::Buffer& x, int m, int g, const cl::Buffer& flow,
                              const DeviceFlowNeighbours& nb, int steps, float weight,
                              float ground_weight, cl::Buffer& d_flow) {
  require(m >= 0 && g >= 0 && m + g > 0,
          "DeviceSceneFlowLoss::run: " + std::to_string(m) + " moving and " + std::to_string(g) +
              " ground points");
  require(steps >= 1 && steps <= 2,
          "DeviceSceneFlowLoss::run: steps = " + std::to_string(steps) + " must be 1 or 2");
  const size_t n = size_t(m) + size_t(g);
  check_floats(x, n * 3, "DeviceSceneFlowLoss::run x");
  check_floats(flow, n * 6, "DeviceSceneFlowLoss::run flow");
  check_floats(d_flow, n * 6, "DeviceSceneFlowLoss::run d_flow");
  if (n > cap_) {
    cap_ = n;
    moved_ = cl::Buffer(rt_, n * 3 * sizeof(float));
    terms_ = cl::Buffer(rt_, n * 6 * sizeof(float));
  }
  // A missing frame leaves its slot 0 and adds nothing to the zeroed gradient.
  slots_.fill_zero();
  d_flow.fill_zero();
  for (int side = 0; side < 2 && m > 0; ++side)  // 0: forward flow to k + s, 1: backward to k − s
    for (int s = 1; s <= steps; ++s) {
      const cl::Buffer* target = side == 0 ? nb.next[s - 1] : nb.prev[s - 1];
      const int nt = side == 0 ? nb.n_next[s - 1] : nb.n_prev[s - 1];
      if (!target || nt <= 0) continue;
      points_.set_args(m, x, flow, side, float(s), moved_);
      launch_1d(points_, size_t(m));
      ChamferGradOut out;
      out.out = &d_flow, out.stride = 6, out.offset = 3 * side, out.mul = float(s);
      out.accumulate = true;
      chamfer_.run(moved_, m, *target, nt, ChamferReduce::Sum, 1.0f, out, slots_, side * 2 + s - 1);
    }
  finish_.set_args(m * 6, int(n) * 6, flow, weight, ground_weight, d_flow, terms_);
  launch_1d(finish_, n * 6);
  chamfer_.sum(g * 6, terms_, ground_weight, 0, terms_, 0.0f, slots_, kGroundSlot);
}

double DeviceSceneFlowLoss::value(const std::vector<float>& slots, double weight) {
  require(slots.size() == size_t(kSlots), "DeviceSceneFlowLoss::value: " +
                                              std::to_string(slots.size()) + " slots");
  double chamfer = 0.0;
  for (int k = 0; k < kGroundSlot; ++k) chamfer += double(slots[size_t(k)]);
  return weight * chamfer + double(slots[kGroundSlot]);
}

double DeviceSceneFlowLoss::read(double weight) const {
  return value(slots_.read_vec<float>(kSlots), weight);
}

}  // namespace sgnlf::render
