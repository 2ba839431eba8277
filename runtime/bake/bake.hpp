// Baking a trained static field into a BakedScene (docs/baking.md): bricks of the voxel lattice
// near the training returns, the field's σ at every vertex of them, bricks where it stops no
// light dropped, then the LiDAR head at every vertex of the bricks kept. The field is reached
// through two callbacks, so this module needs no model: pipeline/run/bake_run.hpp wires a
// trained run's model to them.
#pragma once
#include <functional>
#include <vector>

#include "bake/bake_config.hpp"
#include "bake/baked_scene.hpp"

namespace sgnlf::bake {

struct FieldProbe {
  // σ logits per metre (σ = exp(logit), 1/m) at n world points (n × 3, metres).
  std::function<std::vector<float>(const std::vector<float>& x_m, int n)> density;
  // The head at n world points seen along unit directions (n × 3 each): n × 2 (return
  // probability, intensity), after the sigmoid.
  std::function<std::vector<float>(const std::vector<float>& x_m, const std::vector<float>& dir,
                                   int n)> head;
  // Points per call.
  int batch = 1 << 16;
};

struct BakeInput {
  std::vector<float> returns_m;   // training returns, n × 3 world metres: where surfaces are
  std::vector<float> origins_m;   // the training scans' sensor origins, m × 3: the head's view
  float near_m = 1.0f, far_m = 81.0f;  // the field's render range
};

struct BakeStats {
  long candidate_bricks = 0, kept_bricks = 0;
  long density_rows = 0, head_rows = 0;
  double density_seconds = 0.0, head_seconds = 0.0, seconds = 0.0;
  Json to_json() const;
};

// The head sees each vertex along the direction from the nearest training origin (the view the
// trajectory has of it; docs/baking.md says why). ConfigError when there are no returns or the
// brick grid or count exceeds its limits.
BakedScene bake_field(const BakeConfig& cfg, const BakeInput& in, const FieldProbe& probe,
                      BakeStats* stats = nullptr);

}  // namespace sgnlf::bake
