// Re-seeding of a sequential trajectory's edges after the coarse alignment (not in GeoNLF or
// the paper; docs/method.md §3). A gradient alignment of all poses from the protocol's noisy
// start (≈ 3 m, 20°) can leave one edge (k, k+1) in a local minimum of the Chamfer loss about a
// metre off along the road while the edges around it converge: on kitti360-low-b the relative
// motion of edge 30 → 31 came out 0.96–1.24 m short, every other one within 0.08 m, and no later
// stage moves it back (the confidence graph takes the edges around it as consistent with it).
// The scans alone decide it. A wrong minimum of one edge shows as a spike in the trajectory's
// velocity: edge e's relative motion differs from both neighbours' by more than
// min_difference_m while the neighbours agree with each other within it (at 2 Hz a car's
// speed changes smoothly, so a genuine change of speed moves the neighbours apart too, and a
// step that merely differs from one neighbour is no evidence which of the two is wrong). The
// hypothesis moves the frames e+1 … rigidly so that edge e takes the neighbours' mean motion
// (a rigid move of the suffix changes no other edge); it is refined for `steps` Adam steps at
// the final τ and kept only when the loss of the edges crossing the cut (i ≤ e < j) falls by more
// than min_gain of its value (the current poses refined alike) while the loss of the other
// edges rises by at most min_gain of its own: the refinement moves those too, and its noise
// (about 1 % on kitti360-low-b) must not veto a 14 % gain where the cut is. The first and last edges have one neighbour and are never re-seeded.
//
// The decision may use another residual than the refinement (`judge`): the robust point-to-point
// Chamfer at the final τ scores a metre-short step on a straight road no worse than the right one
// (kitti360-low-b, edge 30 → 31: 0.02319 against 0.02327), while the point-to-plane residual, whose
// plane normals see the along-road offset of every pole and facade, tells them apart. Annealing
// with point-to-plane itself does worse on another twin (docs/studies/pose-reseeding), so the
// hypotheses are refined with the stage's own loss and only judged with `judge`.
//
// A frame can be wrong alone (`frames`): at a sharp turn of nuScenes scene-0916 at 1 Hz one
// frame settles about 42° off in rotation, and both of its edges carry the error, so neither is
// a spike between agreeing neighbours and no edge hypothesis is tried. A frame k whose two edges
// both differ from their outer neighbours ((k-2, k-1) and (k+1, k+2)) by more than
// min_difference_m is a candidate; its hypothesis puts frame k halfway between frames k-1 and
// k+1 (rotation slerped, translation averaged), refined alike and kept under the same rule, with
// the edges that touch k in place of the crossing ones.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"
#include "geometry/se3.hpp"
#include "posegraph/annealed_run.hpp"
#include "posegraph/graph_loss.hpp"

namespace sgnlf::posegraph {

struct ReseedConfig {
  double min_difference_m = 0.3;  // candidate: |t_rel(k) − t_rel(k ± 1)| above this
  int steps = 30;                 // refinement steps per hypothesis (calls of 10, final τ)
  double lr_start = 0.2;          // refinement learning rates: this × the stage's, decaying to
                                  // the stage's lr_final
  double min_gain = 0.02;         // kept when the crossing edges' loss falls by more than this
  int max_rounds = 2;             // passes over the edges (a kept move can expose another)
  // The residual that decides ("point_to_point" or "point_to_plane"; "" = the stage's own).
  std::string judge;
  bool frames = false;  // also single-frame hypotheses (above)
  // The rule for the other edges: false, their loss may rise by at most min_gain of its own;
  // true, the whole graph's loss (every edge, the judge's residual) must fall instead, so a
  // large gain where the cut is may pay for the refinement's noise elsewhere.
  bool judge_total = false;

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("min_difference_m", s.min_difference_m, 0.0, 100.0);
    v("steps", s.steps, 1, 10000);
    v("lr_start", s.lr_start, 1e-6, 1.0);
    v("min_gain", s.min_gain, 0.0, 1.0);
    v("max_rounds", s.max_rounds, 1, 100);
    v("judge", s.judge, config::omit_when(std::string()));  // added later
    v("frames", s.frames, config::omit_when(false));        // added later
    v("judge_total", s.judge_total, config::omit_when(false));  // added later
  }
  // ConfigError naming the field.
  void validate(const std::string& where = "reseed") const;
};

struct ReseedTrial {
  int round = 0;
  int edge = 0;       // k: the edge (k, k+1); for a frame trial, the frame's first edge (k-1, k)
  int frame = -1;     // a frame trial's frame k (its edges' loss is the "crossing" one); -1: an edge trial
  double difference_m = 0.0;       // min over the neighbours of |t_rel(e) − t_rel(e ± 1)|
  double crossing_before = 0.0;    // loss of the edges crossing the cut, current poses refined
  double crossing_after = 0.0;     // the same with the hypothesis, refined
  // The same two with the refinement's own loss (equal to the above without a judge).
  double stage_crossing_before = 0.0, stage_crossing_after = 0.0;
  // The judge's loss of every other edge, before and with the hypothesis (both refined).
  double rest_before = 0.0, rest_after = 0.0;
  // With judge_total: the judge's loss of every edge together, before and with the hypothesis.
  double total_before = 0.0, total_after = 0.0;
  bool kept = false;
};

// The rule of the header on a refined trial's losses: the crossing (or touching) edges' loss
// falls by more than min_gain, and the other edges' rises by at most min_gain of its own (or,
// with judge_total, the whole graph's falls).
bool keep_trial(const ReseedTrial& t, const ReseedConfig& cfg);

struct ReseedResult {
  std::vector<ReseedTrial> trials;
  int kept = 0;
};

// Edges (a, b) of `edges` with a ≤ k < b (either orientation): those crossing the cut after k.
std::vector<Edge> crossing_edges(const std::vector<Edge>& edges, int k);
// Edges of `edges` with frame k at either end.
std::vector<Edge> touching_edges(const std::vector<Edge>& edges, int k);

// The loss that judges the hypotheses: nullptr when cfg.judge is empty or names `base.residual`
// (then `loss` judges). Otherwise the same edges over the same subsample of `scans` (base's
// points_per_frame and seed), with normals from base.normals when the judge needs them.
std::shared_ptr<const GraphLoss> make_judge_loss(const GraphLoss& loss,
                                                 const std::vector<std::vector<PointXYZI>>& scans,
                                                 const GeometricConfig& base,
                                                 const ReseedConfig& cfg);

// Re-seeds T_world_lidar (one pose per frame of `loss`, in order along the trajectory) in place.
// `base` carries the stage's learning rates, τ scale and threads; `lr_final` is the stage's.
// Hypotheses are refined with `loss` and judged with `judge` (make_judge_loss; nullptr: `loss`).
ReseedResult reseed_edges(std::shared_ptr<const GraphLoss> loss, const GeometricConfig& base,
                          double lr_final, const ReseedConfig& cfg,
                          std::vector<Pose>& T_world_lidar,
                          std::shared_ptr<const GraphLoss> judge = nullptr);

Json reseed_json(const ReseedResult& r);

}  // namespace sgnlf::posegraph
