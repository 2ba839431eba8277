// A method: one row a table can name, described once. Its name and description, the preset
// family it trains from (presets/<family>-<scale>.json) with the overrides it applies on top,
// the optional config sections its config carries, and how it composes its step policy from the
// parts (StepParts). One file per method in this folder (lidar_nerf.cpp, geonlf.cpp, sg_nlf.cpp,
// and the control and ablation rows as small derivations of those), listed in registry.cpp.
// Host-only: the config reader (train_config.cpp) builds without OpenCL and reads the sections
// from here; the parts are built on the device by pipeline/train/step_parts.hpp.
#pragma once
#include <string>

#include "core/config.hpp"

namespace sgnlf::pipeline {

class StepPolicy;

// The optional sections of a TrainConfig (train_config.hpp) that a method's config may carry:
// the reader reads only these (another is an unknown key) and resolve_config drops the others
// from the family's presets, so a method without a section (an ablation row) keeps the config
// (and hash) of one that never had it. A carried section is on exactly when present in the
// config (TrainConfig::hybrid_encoder() and its siblings); pose_free is the method's alone.
struct ConfigSections {
  bool pose_free = false;    // poses, pose_optim, reweight, coarse_to_fine, geometric
  bool spectral = false;     // SG-NLF's hybrid field
  bool pose_graph = false;   // SG-NLF's confidence-aware pose graph
  bool consistency = false;  // SG-NLF's adversarial cross-frame consistency
  bool lidar4d = false;      // LiDAR4D's 4D field (encoder, Chamfer term, flow supervision)
};

// The parts a step policy is built from. Each part reads its own config section: one whose
// feature the config turns off is not built and hands back the policy it was given.
class StepParts {
 public:
  virtual ~StepParts() = default;
  // The ground-truth-pose step (LiDAR-NeRF): batches from the scene's poses, one fused step.
  virtual StepPolicy& ground_truth_poses() = 0;
  // The pose-free step (poses are parameters) with the geometric stage before each epoch; with
  // the confidence-aware pose graph when the config turns it on.
  virtual StepPolicy& pose_free() = 0;
  // SG-NLF's adversarial cross-frame consistency (needs pose_free()): a loss term added to the
  // model's list, and around `inner` its logs and checkpoint state.
  virtual StepPolicy& consistency(StepPolicy& inner) = 0;
  // SG-NLF's hybrid field: Ψ trains on the current surface around `inner` (needs pose_free()).
  virtual StepPolicy& spectral(StepPolicy& inner) = 0;
  // LiDAR4D's scene-flow supervision (needs the config's lidar4d section): a loss term added to
  // the model's list, the flow field's loss on the batch frame's ground-removed points in the
  // same Adam step; `inner` is the step.
  virtual StepPolicy& scene_flow(StepPolicy& inner) = 0;
};

struct Method {
  std::string name;           // row name in tables and run.json
  std::string description;
  std::string preset_family;  // presets/<family>-<scale>.json
  Json overrides = Json::object();  // applied on top of the preset, before the user's overrides
  ConfigSections sections;
  bool implemented = false;   // false: a "not implemented" row
  // The method's training step from the parts; null for a method not implemented.
  StepPolicy& (*compose)(StepParts& parts) = nullptr;
};

}  // namespace sgnlf::pipeline
