// The baked scene's surface as a triangle mesh for other tools (`sgnlf bake --ply`,
// docs/baking.md): naive surface nets on the σ logit (a vertex per lattice cell the level set
// crosses, at the mean of its edges' crossings; two triangles per crossed lattice edge whose four
// cells are stored), each vertex carrying the scene's intensity and ray-drop probability
// (1 − return probability) interpolated at it. Written as binary little-endian PLY: vertex
// x y z (float, world metres) intensity drop_probability (float), face vertex_indices
// (uchar count, int indices).
#pragma once
#include <array>
#include <string>
#include <vector>

#include "bake/baked_scene.hpp"

namespace sgnlf::bake {

struct SurfaceMesh {
  std::vector<float> xyz;                      // n × 3, world metres
  std::vector<float> intensity, drop;          // n each
  std::vector<std::array<int, 3>> triangles;   // counter-clockwise seen from outside (σ low)
};

// The level: σ stopping half the light over one voxel (σ·voxel = ln 2), as a logit.
float surface_level(const BakedScene& s);
SurfaceMesh extract_surface(const BakedScene& s, float level_logit);
void write_surface_ply(const std::string& path, const SurfaceMesh& m);

}  // namespace sgnlf::bake
