// Configuration of LiDAR4D's ray-drop refinement U-Net (method.md §2; LiDAR4D's model/unet.py
// and Trainer.refine()): architecture, training schedule, box-dropout augmentation, input
// normalisation, seed. Plain struct with defaults; a strict JSON reader (unknown keys refused,
// naming the key) and a writer for resolved configs.
//
// JSON section, every key optional:
//   {"channels": 32, "depth": 4, "slope": 0.0, "steps": 1000, "lr": 1e-3,
//    "schedule": "one_cycle", "pct_start": 0.3, "div_factor": 25.0, "final_div_factor": 1e4,
//    "beta1": 0.9, "beta2": 0.999, "eps": 1e-8, "weight_decay": 0.0, "boxes_max": 32,
//    "box_frac": 0.1, "depth_scale_m": 80.0, "init_gain": 1.0, "seed": 1}
#pragma once
#include <cstdint>
#include <string>
#include <utility>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::refine {

enum class LrSchedule { one_cycle, constant };
inline constexpr std::pair<LrSchedule, const char*> kLrSchedules[] = {
    {LrSchedule::one_cycle, "one_cycle"}, {LrSchedule::constant, "constant"}};

struct RayDropUNetConfig {
  // Architecture: 1×1 in-conv to `channels`, then `depth` down stages (2×2 max pool, two 3×3
  // convs) to channels·2^min(level, depth − 1), `depth` up stages (bilinear ×2, concatenation
  // with the skip, two 3×3 convs), 1×1 out-conv to one logit. LiDAR4D: 32 and 4.
  int channels = 32;
  int depth = 4;
  float slope = 0.0f;  // activation after every conv but the last: 0 = ReLU (LiDAR4D)
  // Training: full-batch steps of Adam on the mean BCE; LiDAR4D: 1000 steps, lr 1e-3 under
  // PyTorch's OneCycleLR (cosine, pct_start 0.3, div_factor 25, final_div_factor 1e4), Adam
  // (0.9, 0.999), eps 1e-8, no weight decay.
  int steps = 1000;
  float lr = 1e-3f;  // peak learning rate (one_cycle) or the learning rate (constant)
  LrSchedule schedule = LrSchedule::one_cycle;
  float pct_start = 0.3f;
  float div_factor = 25.0f;
  float final_div_factor = 1e4f;
  float beta1 = 0.9f;
  float beta2 = 0.999f;
  float eps = 1e-8f;
  float weight_decay = 0.0f;
  // Box dropout per step (LiDAR4D): k ∈ [0, boxes_max) boxes, each of height in [1, hmax) and
  // width in [1, wmax) with hmax = min(H, max(2, ⌊box_frac·H⌋)), wmax likewise, at a
  // uniform position inside the image; the input is zeroed there. boxes_max = 0: no boxes.
  int boxes_max = 32;
  float box_frac = 0.1f;
  // Input channels (return probability, intensity, depth in metres): depth is divided by this.
  float depth_scale_m = 80.0f;
  // Weights N(0, (init_gain · He std)²), He std = √(2 / ((1 + slope²) · fan_in)); biases 0.
  float init_gain = 1.0f;
  uint64_t seed = 1;  // initialisation and box draws

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("channels", s.channels, 16, 256);
    v("depth", s.depth, 1, 6);
    v("slope", s.slope, 0.0f, 1.0f);
    v("steps", s.steps, 1, 1000000);
    v("lr", s.lr, 0.0f, 1.0f);
    v("schedule", s.schedule, config::choices(kLrSchedules));
    v("pct_start", s.pct_start, 0.0f, 1.0f);
    v("div_factor", s.div_factor, 1.0f, 1e6f);
    v("final_div_factor", s.final_div_factor, 1.0f, 1e8f);
    v("beta1", s.beta1, 0.0f, 0.999999f);
    v("beta2", s.beta2, 0.0f, 0.999999f);
    v("eps", s.eps, 0.0f, 1.0f);
    v("weight_decay", s.weight_decay, 0.0f, 1.0f);
    v("boxes_max", s.boxes_max, 0, 1024);
    v("box_frac", s.box_frac, 0.0f, 1.0f);
    v("depth_scale_m", s.depth_scale_m, 1e-3f, 1e4f);
    v("init_gain", s.init_gain, 1e-6f, 10.0f);
    v("seed", s.seed);
  }

  void validate(const std::string& where = "ray_drop_unet") const;  // throws ConfigError
  static RayDropUNetConfig from_json(const Json& section,
                                     const std::string& where = "ray_drop_unet");
  Json to_json() const;
};

}  // namespace sgnlf::refine
