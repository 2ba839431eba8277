// train_ray_drop (ray_drop_training.hpp).
#include "refine/ray_drop_training.hpp"

#include "refine/box_dropout.hpp"
#include "refine/one_cycle.hpp"

namespace sgnlf::refine {

RayDropTrainResult train_ray_drop(RayDropUNet& net, const cl::Buffer& inputs,
                                  const cl::Buffer& masks, int n, int h, int w,
                                  const std::function<void(int)>& on_progress) {
  const RayDropUNetConfig& cfg = net.config();
  net.check_size(h, w);
  RayDropTrainResult r;
  r.steps = cfg.steps;
  r.initial_loss = net.loss(inputs, masks, n, h, w);
  // Every step's boxes uploaded at once: no host round trip inside the loop.
  const BoxDraws draws = draw_boxes(cfg.seed, cfg.steps, h, w, cfg.boxes_max, cfg.box_frac);
  r.boxes = int(draws.boxes.size() / 4);
  std::vector<int> flat = draws.boxes;
  if (flat.empty()) flat.assign(4, 0);
  const cl::Buffer boxes = cl::Buffer::from(net.runtime(), flat);
  cl::Buffer losses(net.runtime(), size_t(cfg.steps) * sizeof(float));
  for (int s = 0; s < cfg.steps; ++s) {
    net.step(inputs, masks, n, h, w, boxes, draws.first[size_t(s)], draws.count[size_t(s)],
             learning_rate(cfg, s), losses, s);
    if (on_progress && ((s + 1) % kProgressSteps == 0 || s + 1 == cfg.steps)) {
      net.runtime().finish();
      on_progress(s + 1);
    }
  }
  r.loss = losses.read_vec<float>(size_t(cfg.steps));
  r.final_loss = net.loss(inputs, masks, n, h, w);
  return r;
}

}  // namespace sgnlf::refine
