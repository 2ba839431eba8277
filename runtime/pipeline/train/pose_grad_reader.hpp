// Where the pose-free step's pose gradient is summed (the device profile's pose_grad), as one
// strategy chosen when the step is made: host = the per-ray gradients read back (three blocking
// reads of n × 3 floats) and render::pose_gradient in double; device = their sums on the device
// (render::PoseGradSums: Σ dL/do and Σ d × dL/dd in a fixed tree, 6 floats read back) and
// render::pose_gradient_from_world_sums, the sums read with the step's loss values when the
// step reads those (reweighting): its one blocking transfer.
#pragma once
#include <memory>

#include "cl/device_profile.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/train/pose_set.hpp"

namespace sgnlf::pipeline {

class PoseGradReader {
 public:
  virtual ~PoseGradReader() = default;
  // The step's loss values (blocking); `pose_follows`: pose_gradient() of the same step is
  // asked next (the device strategy reads the sums in the same transfer).
  virtual LossReport read_losses(LidarNerfModel& model, bool pose_follows) = 0;
  // dL/dξ of the batch's frame from the last step's ray gradients (blocking).
  virtual Vec6 pose_gradient(LidarNerfModel& model, const Scene& scene, const PoseSet& poses,
                             const RayBatch& b) = 0;
};

std::unique_ptr<PoseGradReader> make_pose_grad_reader(cl::PoseGrad where);

}  // namespace sgnlf::pipeline
