// Training of the ray-drop refinement U-Net after the field (method.md §2; LiDAR4D's
// Trainer.refine()): cfg.steps full-batch steps of Adam on the mean BCE between the U-Net's
// output on the training frames' rendered (return probability, intensity, depth) images, with
// box dropout drawn per step (box_dropout.hpp), and the frames' observed return masks; the
// learning rate per step from one_cycle.hpp. Returns a summary instead of printing.
#pragma once
#include <functional>
#include <vector>

#include "cl/runtime.hpp"
#include "refine/ray_drop_unet.hpp"

namespace sgnlf::refine {

struct RayDropTrainResult {
  std::vector<float> loss;   // BCE of each step (on that step's augmented input)
  double initial_loss = 0;   // inference-mode BCE on the training frames before training
  double final_loss = 0;     // inference-mode BCE on the training frames after training
  int steps = 0;
  int boxes = 0;             // boxes drawn over all steps
};

// Trains `net` from its current parameters and Adam state (call net.reset() for a fresh start)
// on n frames of h × w: inputs n × h × w × 3 (depth in metres), masks n × h × w (1 = return,
// 0 = dropped ray). Blocks until done; the box draws depend on cfg.seed alone. `on_progress`,
// when set, is called with the steps done every kProgressSteps steps (the queue is waited for
// there; the result does not change).
inline constexpr int kProgressSteps = 10;
RayDropTrainResult train_ray_drop(RayDropUNet& net, const cl::Buffer& inputs,
                                  const cl::Buffer& masks, int n, int h, int w,
                                  const std::function<void(int)>& on_progress = {});

}  // namespace sgnlf::refine
