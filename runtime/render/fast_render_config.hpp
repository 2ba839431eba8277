// Configuration of the fast renderer for trained fields (`sgnlf render`'s default; the tables
// keep the protocol's renderer): its occupancy grid (render::OccupancyGrid), early ray
// termination and the LiDAR head's weight threshold. Host-only.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::render {

struct FastRenderConfig {
  // The occupancy grid: cells of cell_m metres over the scene's points' box grown by margin_m;
  // a cell is occupied when it holds a return of a training scan (under the run's poses) or exp(σ)·δ at one of its probes³ stratified probe points exceeds
  // −log(1 − alpha) (one sample there, δ the renderer's bin width, would stop more than alpha
  // of the light), then dilated by `dilate` cells. Refused above max_cells cells.
  // Defaults measured on SG-NLF quick fields of kitti360-low-a, opaque and translucent
  // (docs/studies/fast-render): 1 m cells probed at their centres (probes 1 m apart, as 2 m
  // cells with 2³ probes were) and waves doubling up to 8 cut the opaque field's density rows
  // from 258 to 126 per ray, every test-view metric within 0.02 dB and 0.1 % of the protocol's.
  float cell_m = 1.0f;
  int probes_per_axis = 1;
  float alpha = 1e-4f;
  int dilate = 1;
  float margin_m = 2.0f;
  int max_cells = 1 << 26;
  // Marching: samples in occupied cells are evaluated front to back in waves (`wave` samples
  // per ray, doubling, one host sync per wave; wave max_waves takes every sample left) until
  // the transmittance falls below stop_transmittance; the head runs on samples whose weight
  // exceeds head_weight_threshold.
  float stop_transmittance = 1e-4f;
  float head_weight_threshold = 1e-4f;
  int wave = 8;
  int max_waves = 8;
  // Where the samples are. "protocol": the protocol renderer's own samples (uniform, and
  // importance samples from a marched coarse pass), of which those in free cells are skipped
  // (pipeline::FastMarch). "march": samples placed by the grid (pipeline::GridMarch): a lattice
  // `refine` times finer than the protocol's bins in occupied cells, free cells jumped over,
  // the protocol's spacing outside the grid's box; no importance pass. Occupied cells are
  // walked at the protocol's spacing too until a sample there stops more than hit_alpha of the
  // light; the ray then rewinds one bin and walks the fine lattice until `refine` fine samples
  // in a row stay below hit_alpha (0: every occupied cell at the fine lattice). In "march"
  // every wave takes `wave` samples per ray (max_waves is not read) until every ray has
  // stopped: a hit drops the rest of its wave, so larger or doubling waves cost more rows
  // (docs/studies/fast-render).
  // `coarse`: bins per step in occupied cells before a hit (the protocol's spacing at 1).
  std::string layout = "protocol";
  int refine = 4;
  float hit_alpha = 1e-3f;
  int coarse = 1;

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("cell_m", s.cell_m, 1e-3f, 1e3f);
    v("probes_per_axis", s.probes_per_axis, 1, 8);
    v("alpha", s.alpha, 1e-9f, 0.5f);
    v("dilate", s.dilate, 0, 8);
    v("margin_m", s.margin_m, 0.0f, 1e3f);
    v("max_cells", s.max_cells, 1, 1 << 30);
    v("stop_transmittance", s.stop_transmittance, 0.0f, 0.5f);
    v("head_weight_threshold", s.head_weight_threshold, 0.0f, 0.1f);
    v("wave", s.wave, 1, 1 << 16);
    v("max_waves", s.max_waves, 1, 1 << 16);
    v("layout", s.layout);
    v("refine", s.refine, 1, 64);
    v("hit_alpha", s.hit_alpha, 0.0f, 0.5f);
    v("coarse", s.coarse, 1, 16);
  }
  void validate(const std::string& where = "fast_render") const;
  // All keys optional (the others as in `base`), unknown keys rejected, validated.
  static FastRenderConfig from_json(const Json& j, const std::string& where,
                                    const FastRenderConfig& base);
  static FastRenderConfig from_json(const Json& j, const std::string& where = "fast_render");
  // The grid-placed layout with the settings measured on SG-NLF's and LiDAR-NeRF's quick
  // fields (docs/studies/fast-render, "Samples placed by the grid"): refine 4, hit_alpha 1e-2,
  // coarse steps of 2 bins, termination and head thresholds 1e-3, waves of 8.
  static FastRenderConfig march();
  Json to_json() const;
};

}  // namespace sgnlf::render
