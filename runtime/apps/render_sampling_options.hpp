// `--samples N --importance M --depth expected|median|mix --out-of-range drop|keep` on the
// commands that render a trained run (eval, render): pipeline::RenderSampling, the run's config
// values unless given (pipeline/run/run_dir.hpp).
#pragma once
#include "apps/command.hpp"
#include "pipeline/run/run_dir.hpp"

namespace sgnlf::app {

inline void add_render_sampling_options(CLI::App& sub, pipeline::RenderSampling& s) {
  sub.add_option("--samples", s.n_samples,
                 "Uniform samples per ray when rendering (default: the config's render.eval_samples, else as trained)");
  sub.add_option("--importance", s.n_importance,
                 "Importance samples per ray when rendering (default: the config's render.eval_importance, else as trained)");
  sub.add_option("--depth", s.depth,
                 "Rendered depth: expected (sum of w_i t_i, as trained and published), median "
                 "(where the accumulated weight reaches 1/2) or mix (the median on the rays "
                 "whose depth variance exceeds 10x the frame's median, GS-LiDAR's; protocol "
                 "renderer). Default: the config's render.eval_depth, else expected")
      ->check(CLI::IsMember({"expected", "median", "mix"}));
  sub.add_option("--out-of-range", s.out_of_range,
                 "drop: a rendered return at a range the sensor cannot report (within its "
                 "min_range_m or beyond max_range_m) is a drop; keep: scored as rendered. "
                 "Default: the config's render.eval_drop_out_of_range, else keep")
      ->check(CLI::IsMember({"drop", "keep"}));
}

}  // namespace sgnlf::app
