// Learning rate per step of LiDAR4D's ray-drop refinement: PyTorch's OneCycleLR with cosine
// annealing (two phases, the default): from lr / div_factor up to lr over the first
// pct_start · steps steps, then down to lr / (div_factor · final_div_factor) at the last step,
// each phase lr_end + (lr_start − lr_end) · (1 + cos(π · t)) / 2. PyTorch also cycles Adam's β1
// (0.85 ↔ 0.95) by default; here β1 stays fixed (field::Adam has one β1), a stated deviation.
#pragma once
#include "refine/ray_drop_unet_config.hpp"

namespace sgnlf::refine {

// Learning rate of step i (0-based) of cfg.steps under cfg.schedule.
float learning_rate(const RayDropUNetConfig& cfg, int step);

}  // namespace sgnlf::refine
