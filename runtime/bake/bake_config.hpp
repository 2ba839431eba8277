// Settings of `sgnlf bake` (bake.hpp): the voxel lattice of the baked scene, where bricks are
// kept, and the ray caster's march (ray_caster.hpp). Host-only; JSON with unknown keys refused.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::bake {

struct BakeConfig {
  // Lattice: vertices voxel_m apart, bricks of brick³ cells ((brick + 1)³ vertices each, so a
  // sample's trilinear lookup never leaves its brick). Bricks are kept where a training return
  // lies within dilate_m of them and the field's density at one of their vertices would stop
  // more than min_alpha of the light over one march step (docs/baking.md).
  float voxel_m = 0.1f;
  int brick = 8;
  float dilate_m = 0.3f;
  float min_alpha = 1e-4f;
  // Ray caster: samples step_m apart along the ray on a lattice from near (the run's
  // render.near_m), stopped once the transmittance falls below stop_transmittance.
  // step_m 0: the voxel size.
  float step_m = 0.0f;
  float stop_transmittance = 1e-4f;
  // Refused above this many bricks (memory: (brick + 1)³ × 16 bytes each).
  int max_bricks = 1 << 20;

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("voxel_m", s.voxel_m, 1e-3f, 10.0f);
    v("brick", s.brick, 2, 32);
    v("dilate_m", s.dilate_m, 0.0f, 10.0f);
    v("min_alpha", s.min_alpha, 0.0f, 0.5f);
    v("step_m", s.step_m, 0.0f, 10.0f);
    v("stop_transmittance", s.stop_transmittance, 0.0f, 0.5f);
    v("max_bricks", s.max_bricks, 1, 1 << 28);
  }
  void validate(const std::string& where = "bake") const;
  float step() const { return step_m > 0.0f ? step_m : voxel_m; }
  // All keys optional (the others as in `base`), unknown keys refused, validated.
  static BakeConfig from_json(const Json& j, const std::string& where, const BakeConfig& base);
  static BakeConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::bake
