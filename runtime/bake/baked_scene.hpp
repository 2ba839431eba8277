// A trained field baked into a sparse explicit scene (`sgnlf bake`, docs/baking.md): a lattice
// of vertices voxel_m apart in the run's world frame (metres), grouped into bricks of brick³
// cells that are kept only near the surfaces. Each brick holds its own (brick + 1)³ vertices
// (faces shared with a neighbour are stored twice), so a trilinear lookup reads one brick. Per
// vertex: the σ logit per metre (σ = exp(logit), 1/m), the LiDAR head's return probability and
// intensity (after the sigmoid), all interpolated trilinearly by the ray caster.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/config.hpp"

namespace sgnlf::bake {

// The vertex record the ray caster gathers: one float4.
struct BakedVertex {
  float logit = -30.0f;  // σ = exp(logit) per metre
  float ret = 0.0f;      // return probability (sigmoid of the head's first output)
  float intensity = 0.0f;
  float pad = 0.0f;
};

struct BakedScene {
  float voxel_m = 0.1f;
  int brick = 8;                          // cells per brick side
  std::array<double, 3> origin_m{};       // world position of brick (0, 0, 0)'s first vertex
  std::array<int, 3> dims{};              // bricks per axis, x fastest in `index`
  std::vector<int32_t> index;             // brick slot, or −1 where nothing is stored
  std::vector<BakedVertex> vertices;      // slots × (brick + 1)³, x fastest within a brick
  // The render range and march of the field it was baked from (metres).
  float near_m = 1.0f, far_m = 81.0f, step_m = 0.1f, stop_transmittance = 1e-4f;
  Json provenance = Json::object();       // run, step, method, config, bake seconds

  int vertices_per_brick() const { return (brick + 1) * (brick + 1) * (brick + 1); }
  size_t bricks() const { return index.empty() ? 0 : vertices.size() / size_t(vertices_per_brick()); }
  double brick_m() const { return double(voxel_m) * brick; }
  // Bytes of the arrays the ray caster reads (index, vertices and the cell mask).
  size_t bytes() const {
    return index.size() * 4 + vertices.size() * sizeof(BakedVertex) + bricks() * size_t(mask_words()) * 4;
  }
  // The ray caster's cell mask: per brick, a bit per cell (x fastest, 32 a word), set when one
  // of the cell's 8 vertices has logit ≥ skip_logit; a sample in a clear cell is skipped.
  float skip_logit = -30.0f;
  int mask_words() const { return (brick * brick * brick + 31) / 32; }
  std::vector<uint32_t> cell_mask() const;
  // Throws NumericError naming the first inconsistency (sizes, slots out of range).
  void validate(const std::string& where = "baked scene") const;
  // World position (metres) of vertex (i, j, k) of the brick at brick coordinates (bx, by, bz).
  std::array<double, 3> vertex_position(const std::array<int, 3>& b, int i, int j, int k) const;
};

// SCENE file: "SGNLFBAK", a uint32 version, a uint64 header length, the header JSON (geometry,
// march, provenance), then index (int32) and vertices (4 float32 each), little-endian.
void write_baked_scene(const std::string& path, const BakedScene& s);
BakedScene read_baked_scene(const std::string& path);  // IoError naming the file and field

}  // namespace sgnlf::bake
