// Configuration of SG-NLF's confidence-aware pose graph in a pose-free run (method.md §4.2), the
// config's "pose_graph" section: when the geometric stage's refinement switches from GeoNLF's
// sequential graph to the confidence graph (built from the field's f_hyb under the current
// poses), and the graph's own parameters (posegraph::ConfidenceGraphConfig, whose
// reevaluate_every counts epochs here). Present only in the configs of methods with the
// confidence graph (ConfigSections::pose_graph, methods/); on exactly when present (absent: the
// sequential graph throughout, the ablation "without global graph").
#pragma once
#include "core/config_fwd.hpp"
#include "posegraph/confidence_graph_config.hpp"

namespace sgnlf::pipeline {

struct PoseGraphConfig {
  // First epoch whose geometric refinement uses the confidence graph: the field has to be
  // trained enough for f_hyb to describe the surface, and the sequential graph converged
  // (method.md §4.2 "Caution"). Epoch 0 is always the sequential coarse alignment.
  int start_epoch = 10;
  // Each time the graph is (re)built, before the epoch's refinement, a pose-only run over the
  // new graph of round(steps_on_build · (1 − progress / geometric.stop_progress)) steps in calls
  // of 10, the learning rates decaying from lr_on_build to geometric.lr_final times the
  // geometric stage's rates. GeoNLF's refinement (a few steps per epoch at the final rates) moves
  // a drifted loop by centimetres per epoch: measured on kitti360-loop, 0.787 → 0.749 m ATE over
  // the seven epochs after the first build (docs/studies/sgnlf-loop). 0: no such run.
  int steps_on_build = 0;
  double lr_on_build = 0.25;
  posegraph::ConfidenceGraphConfig graph;  // its keys sit in the same "pose_graph" object

  // This struct's own keys and ranges (core/config_fields.hpp).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("start_epoch", s.start_epoch, 1, 100000000);
    v("steps_on_build", s.steps_on_build, 0, 1000000);
    v("lr_on_build", s.lr_on_build, 1e-6, 1.0);
  }

  void validate(const std::string& where) const;
  static PoseGraphConfig from_json(ConfigReader& r);  // reads "pose_graph"; errors name r.where()
  void to_json(Json& j) const;                        // adds the "pose_graph" section
};

}  // namespace sgnlf::pipeline
