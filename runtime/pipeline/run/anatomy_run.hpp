// The error anatomy of a trained run's test views (metrics/anatomy.hpp, docs/anatomy.md) beside
// the nearest-scan baseline's: where each CD direction and the depth MSE come from, by cause,
// range band, beam row and distance to the training scans.
#pragma once
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "geometry/range_image.hpp"
#include "pipeline/run/run_dir.hpp"

namespace sgnlf::pipeline {

// A run's test views in test-split order, as eval_run renders and scores them: the model's
// prediction (after the ray-drop U-Net, when the run has one) and the naive baseline's view.
struct TestViewImages {
  std::vector<RangeImage> model, naive;
};

// Renders the test views as eval_run does, unless `rendered` holds them, and writes
// <out_dir>/anatomy.json (per frame and mean, model and naive baseline; keys in
// metrics/anatomy_json.hpp) and <out_dir>/anatomy/<frame id>.png (the masked rendering, the
// nearest scan's view, both with false returns magenta and missed returns white, above the
// observed scan). The training scans' points are placed with the poses the naive baseline
// uses (the reference poses, else the run's). Returns anatomy.json's contents. Error when
// `rendered` does not hold one image per test frame.
Json anatomy_run(LoadedRun& run, const std::string& out_dir,
                 const TestViewImages* rendered = nullptr);

}  // namespace sgnlf::pipeline
