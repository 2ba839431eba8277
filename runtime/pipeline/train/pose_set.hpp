// The poses of a pose-free run as parameters (method.md §0 "Poses"): per frame a correction
// ξ_i = (ω_i, u_i), T_world_lidar,i = T_init,i · [Exp_SO3(ω_i) | u_i] (no left Jacobian), all in
// the normalised scene frame, zero-initialised, each frame with its own Adam state (a frame's
// correction only moves on the steps whose rays came from it, as with PyTorch's Adam over
// parameters without a gradient). Learning rates decay exponentially to lr·final_factor.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "geometry/se3.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/config/pose_free_config.hpp"

namespace sgnlf::pipeline {

class PoseSet {
 public:
  // `lr_scale` multiplies both learning rates (identity init: PoseOptimConfig::lr_scale).
  PoseSet(std::vector<Pose> T_init, const PoseOptimConfig& c, double lr_scale = 1.0);

  size_t size() const { return T_init_.size(); }
  const Pose& initial(size_t i) const { return T_init_.at(i); }
  const Vec6& correction(size_t i) const { return xi_.at(i); }
  Pose pose(size_t i) const;
  std::vector<Pose> poses() const;

  // One Adam step of frame i's correction from g = (dL/dω, dL/du) at training progress ∈ [0, 1],
  // plus the frame's pending gradient (added, then cleared) when it has one.
  void step(size_t i, const Vec6& g, double progress);
  // Pending gradient: a term computed outside frame i's own step (SG-NLF's cross-frame
  // consistency, consistency_schedule.hpp) is summed here and joins frame i's next step(), so
  // that each frame keeps one Adam step per visit and the term's weight stays a weight
  // relative to the range loss (a separate Adam step would normalise it away).
  void add_pending(size_t i, const Vec6& g);
  bool has_pending(size_t i) const { return pending_on_.at(i) != 0; }
  void drop_pending(size_t i) { pending_.at(i).setZero(), pending_on_.at(i) = 0; }
  const Vec6& pending(size_t i) const { return pending_.at(i); }
  // Checkpoint form: 7 doubles per frame (flag, then the gradient), and its restoration.
  std::vector<double> pending_flat() const;
  void set_pending_flat(const std::vector<double>& flat);
  // Re-expresses T as frame i's correction: ω = Log(R_initᵀ R), u = R_initᵀ (t − t_init).
  // Adam moments are kept. Throws NumericError for a non-finite pose.
  void set_pose(size_t i, const Pose& T);

  // Checkpoint arrays ("poses.xi", "poses.adam_m", "poses.adam_v", "poses.adam_t"): doubles
  // stored bit-exactly (two float slots each) so that a resumed run is bit-identical.
  std::vector<std::pair<std::string, std::vector<float>>> state_arrays() const;
  // Restores from arrays returned by `lookup(name, expected_float_count)`.
  template <typename Lookup>
  void load_state(Lookup&& lookup) {
    const size_t n = 6 * size();
    xi_flat_from(unpack_doubles(lookup("poses.xi", 2 * n)));
    m_ = to_vec6(unpack_doubles(lookup("poses.adam_m", 2 * n)));
    v_ = to_vec6(unpack_doubles(lookup("poses.adam_v", 2 * n)));
    const auto t = unpack_doubles(lookup("poses.adam_t", 2 * size()));
    for (size_t i = 0; i < size(); ++i) t_[i] = long(t[i]);
  }

 private:
  std::vector<Vec6> to_vec6(const std::vector<double>& flat) const;
  void xi_flat_from(const std::vector<double>& flat) { xi_ = to_vec6(flat); }

  std::vector<Pose> T_init_;
  PoseOptimConfig cfg_;
  double lr_scale_;
  std::vector<Vec6> xi_, m_, v_;
  std::vector<long> t_;
  std::vector<Vec6> pending_;
  std::vector<char> pending_on_;
};

}  // namespace sgnlf::pipeline
