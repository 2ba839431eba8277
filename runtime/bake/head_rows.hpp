// Where a cast ray's LiDAR head is evaluated (docs/baking.md, "the field head"): the field's
// renderer sums w·head over the ray's weight, so one row at the ray's surface point stands for
// it where the weight lies within `spread_m` (the 1/8 and 7/8 quartile depths, or those the ray
// reached, no further apart), else one row at each quartile it reached, equally weighted.
// Rays that meet nothing (opacity ≤ 1e-4) get none. The baked renderer's field head
// (pipeline/model/baked_renderer.hpp). Host-only.
#pragma once
#include <cstddef>
#include <vector>

namespace sgnlf::bake {

struct HeadRow {
  size_t ray = 0;
  float t_m = 0.0f;     // distance along the ray (metres)
  float weight = 0.0f;  // its share of the ray's opacity: Σ over a ray's rows = its opacity
};

// `cast`: n rays × RayCaster::kOutputs floats (ray_caster.hpp). `spread_rays`, when given,
// counts the rays that took quartile rows.
std::vector<HeadRow> head_rows(const std::vector<float>& cast, size_t n, float spread_m,
                               long* spread_rays = nullptr);

}  // namespace sgnlf::bake
