// reseed_edges (see edge_reseeding.hpp).
#include "posegraph/edge_reseeding.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"

namespace sgnlf::posegraph {

void ReseedConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  if (!(judge.empty() || judge == "point_to_point" || judge == "point_to_plane"))
    throw ConfigError(where + ".judge = \"" + judge +
                      "\": must be \"point_to_point\", \"point_to_plane\" or \"\" (the "
                      "stage's residual)");
}

std::shared_ptr<const GraphLoss> make_judge_loss(const GraphLoss& loss,
                                                 const std::vector<std::vector<PointXYZI>>& scans,
                                                 const GeometricConfig& base,
                                                 const ReseedConfig& cfg) {
  cfg.validate();
  if (cfg.judge.empty() || cfg.judge == base.residual) return nullptr;
  require(scans.size() == loss.frames(), "make_judge_loss: " + std::to_string(scans.size()) +
                                             " scans for " + std::to_string(loss.frames()) +
                                             " frames");
  GeometricConfig j = base;
  j.residual = cfg.judge;
  auto clouds = std::make_shared<const std::vector<FrameCloud>>(j.clouds(scans));
  return std::make_shared<const GraphLoss>(clouds, loss.edges(), loss.min_distance(), base.threads,
                                           j.direction(), loss.max_distance());
}

std::vector<Edge> crossing_edges(const std::vector<Edge>& edges, int k) {
  std::vector<Edge> out;
  for (const Edge& e : edges)
    if (std::min(e.i, e.j) <= k && std::max(e.i, e.j) > k) out.push_back(e);
  return out;
}

std::vector<Edge> touching_edges(const std::vector<Edge>& edges, int k) {
  std::vector<Edge> out;
  for (const Edge& e : edges)
    if (e.i == k || e.j == k) out.push_back(e);
  return out;
}

namespace {

// T_k⁻¹ · T_{k+1}.
Pose relative(const std::vector<Pose>& T, int k) { return T[size_t(k)].inverse() * T[size_t(k) + 1]; }

double loss_at(const GraphLoss& loss, const std::vector<Pose>& T, double tau) {
  std::vector<PoseGrad> g;
  return loss(T, tau, g);
}

}  // namespace

ReseedResult reseed_edges(std::shared_ptr<const GraphLoss> loss, const GeometricConfig& base,
                          double lr_final, const ReseedConfig& cfg, std::vector<Pose>& T,
                          std::shared_ptr<const GraphLoss> judge) {
  require(loss != nullptr, "reseed_edges: null loss");
  if (!judge) judge = loss;
  require(judge->frames() == loss->frames(), "reseed_edges: the judge has " +
                                                 std::to_string(judge->frames()) + " frames, the loss " +
                                                 std::to_string(loss->frames()));
  cfg.validate();
  require(T.size() == loss->frames(), "reseed_edges: " + std::to_string(T.size()) +
                                          " poses for " + std::to_string(loss->frames()) +
                                          " frames");
  ReseedResult out;
  const int n = int(T.size());
  if (n < 3) return out;
  const double tau = base.tau_scale;  // the final τ (progress 1)
  AnnealConfig refine;
  refine.steps = cfg.steps;
  refine.lr_start = cfg.lr_start;
  refine.lr_final = std::min(lr_final, cfg.lr_start);
  refine.hold_clock = true;
  const auto polish = [&](std::vector<Pose>& P) { run_annealed(loss, base, refine, P); };

  // The current poses get the same refinement as a hypothesis, so that the two are compared
  // alike; made again only after a kept move.
  std::vector<Pose> cur;
  bool cur_valid = false;
  // Refines `cand` and judges it against the current poses on `local_edges` (the judge's: the
  // edges crossing the cut, or touching the frame) and on every other edge; keeps it under the
  // rule of the header. Fills t's losses and t.kept.
  const auto judge_hypothesis = [&](const std::vector<Edge>& local_edges,
                                    const std::vector<Edge>& stage_edges, std::vector<Pose> cand,
                                    ReseedTrial& t) {
    const GraphLoss local(judge->clouds(), local_edges, judge->min_distance(), 1,
                          judge->direction(), judge->max_distance());
    const GraphLoss stage_local(loss->clouds(), stage_edges, loss->min_distance(), 1,
                                loss->direction(), loss->max_distance());
    std::vector<Edge> rest_edges;  // the others: a rigid move leaves them alone, the refinement not
    for (const Edge& x : judge->edges())
      if (std::find_if(local_edges.begin(), local_edges.end(), [&](const Edge& y) {
            return y.i == x.i && y.j == x.j;
          }) == local_edges.end())
        rest_edges.push_back(x);
    std::optional<GraphLoss> rest;
    if (!rest_edges.empty())
      rest.emplace(judge->clouds(), rest_edges, judge->min_distance(), base.threads,
                   judge->direction(), judge->max_distance());
    if (!cur_valid) {
      cur = T;
      polish(cur);
      cur_valid = true;
    }
    t.crossing_before = loss_at(local, cur, tau);
    t.stage_crossing_before = loss_at(stage_local, cur, tau);
    t.rest_before = rest ? loss_at(*rest, cur, tau) : 0.0;
    polish(cand);
    t.crossing_after = loss_at(local, cand, tau);
    t.stage_crossing_after = loss_at(stage_local, cand, tau);
    t.rest_after = rest ? loss_at(*rest, cand, tau) : 0.0;
    if (cfg.judge_total) {
      const GraphLoss all(judge->clouds(), judge->edges(), judge->min_distance(), base.threads,
                          judge->direction(), judge->max_distance());
      t.total_before = loss_at(all, cur, tau);
      t.total_after = loss_at(all, cand, tau);
    }
    t.kept = keep_trial(t, cfg);
    out.trials.push_back(t);
    if (t.kept) {
      T = std::move(cand);
      cur_valid = false;
      ++out.kept;
    }
    return t.kept;
  };
  for (int round = 0; round < cfg.max_rounds; ++round) {
    int kept_this_round = 0;
    // A spike: edge e's motion differs from both neighbours' by more than min_difference_m while
    // the neighbours agree with each other within it. Its hypothesis is their mean motion.
    for (int e = 1; e + 2 < n; ++e) {
      const Pose a = relative(T, e - 1), c = relative(T, e), b = relative(T, e + 1);
      const double d_a = (c.translation() - a.translation()).norm();
      const double d_b = (c.translation() - b.translation()).norm();
      const double d_ab = (a.translation() - b.translation()).norm();
      if (!(d_a > cfg.min_difference_m && d_b > cfg.min_difference_m &&
            d_ab <= cfg.min_difference_m))
        continue;
      ReseedTrial t;
      t.round = round, t.edge = e, t.difference_m = std::min(d_a, d_b);
      // The hypothesis: frames e+1 … moved rigidly so that edge e takes the neighbours' mean
      // motion (a rigid move of the suffix changes no other edge).
      const Eigen::Quaterniond qa(a.rotation()), qb(b.rotation());
      Pose hyp = Pose::Identity();
      hyp.linear() = qa.slerp(0.5, qb).toRotationMatrix();
      hyp.translation() = 0.5 * (a.translation() + b.translation());
      std::vector<Pose> cand = T;
      const Pose C = (T[size_t(e)] * hyp) * T[size_t(e) + 1].inverse();
      for (int j = e + 1; j < n; ++j) cand[size_t(j)] = C * T[size_t(j)];
      kept_this_round += judge_hypothesis(crossing_edges(judge->edges(), e),
                                          crossing_edges(loss->edges(), e), std::move(cand), t);
    }
    // A frame alone: both of frame k's edges differ from their outer neighbours'. Its
    // hypothesis is frame k halfway between frames k-1 and k+1.
    for (int k = 2; cfg.frames && k + 2 < n; ++k) {
      const Pose a = relative(T, k - 2), e1 = relative(T, k - 1), e2 = relative(T, k),
                 b = relative(T, k + 1);
      const double d1 = (e1.translation() - a.translation()).norm();
      const double d2 = (e2.translation() - b.translation()).norm();
      if (!(d1 > cfg.min_difference_m && d2 > cfg.min_difference_m)) continue;
      ReseedTrial t;
      t.round = round, t.edge = k - 1, t.frame = k, t.difference_m = std::min(d1, d2);
      const Pose& P = T[size_t(k) - 1];
      const Pose& N = T[size_t(k) + 1];
      const Eigen::Quaterniond qp(P.rotation()), qn(N.rotation());
      std::vector<Pose> cand = T;
      cand[size_t(k)].linear() = qp.slerp(0.5, qn).toRotationMatrix();
      cand[size_t(k)].translation() = 0.5 * (P.translation() + N.translation());
      kept_this_round += judge_hypothesis(touching_edges(judge->edges(), k),
                                          touching_edges(loss->edges(), k), std::move(cand), t);
    }
    if (kept_this_round == 0) break;
  }
  return out;
}

bool keep_trial(const ReseedTrial& t, const ReseedConfig& cfg) {
  const bool local = std::isfinite(t.crossing_after) &&
                     t.crossing_after < (1.0 - cfg.min_gain) * t.crossing_before;
  const bool rest = cfg.judge_total ? t.total_after < t.total_before
                                    : t.rest_after <= (1.0 + cfg.min_gain) * t.rest_before;
  return local && rest;
}

Json reseed_json(const ReseedResult& r) {
  Json trials = Json::array();
  for (const auto& t : r.trials) {
    Json j{{"round", t.round}};
    if (t.frame >= 0)
      j["frame"] = t.frame;
    else
      j["edge"] = Json::array({t.edge, t.edge + 1});
    j.update(Json{{"difference_m", t.difference_m},
                  {"crossing_before", t.crossing_before},
                  {"crossing_after", t.crossing_after},
                  {"stage_crossing_before", t.stage_crossing_before},
                  {"stage_crossing_after", t.stage_crossing_after},
                  {"rest_before", t.rest_before},
                  {"rest_after", t.rest_after},
                  {"kept", t.kept}});
    if (t.total_before != 0.0 || t.total_after != 0.0)  // judge_total
      j.update(Json{{"total_before", t.total_before}, {"total_after", t.total_after}});
    trials.push_back(j);
  }
  return Json{{"kept", r.kept}, {"trials", trials}};
}

}  // namespace sgnlf::posegraph
