// learning_rate (one_cycle.hpp), in double as PyTorch computes it, then rounded to float.
#include "refine/one_cycle.hpp"

#include <cmath>

namespace sgnlf::refine {

float learning_rate(const RayDropUNetConfig& cfg, int step) {
  if (cfg.schedule == LrSchedule::constant) return cfg.lr;
  const double max_lr = cfg.lr, initial = max_lr / cfg.div_factor;
  const double min_lr = initial / cfg.final_div_factor;
  const double end_up = double(cfg.pct_start) * cfg.steps - 1.0, end_down = cfg.steps - 1.0;
  auto anneal = [](double from, double to, double t) {
    return to + (from - to) / 2.0 * (std::cos(M_PI * t) + 1.0);
  };
  if (step <= end_up) return float(anneal(initial, max_lr, end_up > 0 ? step / end_up : 1.0));
  const double span = end_down - end_up;
  return float(anneal(max_lr, min_lr, span > 0 ? (step - end_up) / span : 1.0));
}

}  // namespace sgnlf::refine
