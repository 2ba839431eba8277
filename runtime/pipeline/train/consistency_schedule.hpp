// SG-NLF's adversarial cross-frame consistency in pose-free training (method.md §4.3–4.4) as a
// loss term of the model (ConsistencyLoss: its own pass through the field, loss_term.hpp), and
// the StepPolicy around the pose-free step that logs it and carries its state in checkpoints
// (ConsistencySchedule). At the steps the config's "consistency" section selects (every `every`
// steps from `warmup_steps`), the term's pass, ahead of the batch's within the model's step:
//  - the pair: i = the step's batch frame, j = i ± one of the configured offsets, drawn from
//    (seed, step); both trainable (not pose-only), else the step has no consistency term;
//  - ConsistencyTerm::run: render i at its current pose, reproject into j, one discriminator
//    step, L_con's gradient λ_con·dL_con into the field (the step's gradient: one Adam step on
//    one objective) and into ξ_i, ξ_j;
//  - the pose gradients go to PoseSet's pending gradients (pose_set.hpp): ξ_i's joins frame i's
//    range-loss pose gradient in this step's pose Adam step; frame j's translation gradient
//    (its rotation gets none) waits, summed, for frame j's next own step (at most an epoch
//    later): every frame keeps one Adam step per visit, so λ_con stays a relative weight for the
//    poses as for the field. It is computed at frame j's pose of that moment.
// It renders with the step's coarse-to-fine mask and λ(t) (StepPolicy::set_schedules). Its value λ_con·L_con is reported as "consistency", out
// of the divergence check's total (an adversarial generator loss has no lower bound).
// Logs (train_log.jsonl "consistency"): L_D, L_con, mean D(real) / D(fake), mask coverage,
// the pair, of the last consistency step. Checkpoints carry the discriminator's parameters and
// Adam state, the pending pose gradients and the last values, so a resumed run is bit-identical.
#pragma once
#include <vector>

#include "pipeline/train/consistency_term.hpp"
#include "pipeline/train/pose_set.hpp"
#include "pipeline/train/step_policy.hpp"

namespace sgnlf::pipeline {

class ConsistencyLoss final : public LossTerm {
 public:
  ConsistencyLoss(cl::Runtime& rt, const Scene& scene, const TrainConfig& cfg, PoseSet& poses,
                  int max_rays, uint64_t seed);

  const char* name() const override { return "consistency"; }
  void add_field_gradient(FieldPass& field) override;
  void report(LossReport& r, const std::vector<float>&) const override;

  // The pair of `step` (i = batch frame), or {-1, -1} when the step has none.
  std::pair<int, int> pair_at(uint64_t seed, long step) const;
  ConsistencyTerm& term() { return term_; }
  long steps_taken() const { return steps_; }
  double seconds() const { return seconds_; }  // consistency steps of this process
  Json log_fields() const;
  const ConsistencyResult& last() const { return last_; }
  NamedArrays state() const;
  void load_state(const Checkpoint& ck);

 private:
  bool trainable(int f) const;

  const Scene& scene_;
  const TrainConfig& cfg_;
  PoseSet& poses_;
  uint64_t seed_;
  ConsistencyTerm term_;
  ConsistencyResult last_;
  int last_i_ = -1, last_j_ = -1;
  long last_step_ = -1, steps_ = 0;
  double seconds_ = 0.0;
};

// The consistency term's logs, progress text and checkpoint state around `inner`; the term
// itself runs in the model's step.
class ConsistencySchedule : public StepPolicy {
 public:
  ConsistencySchedule(StepPolicy& inner, ConsistencyLoss& loss) : inner_(inner), loss_(loss) {}

  void on_epoch(long epoch, long step) override { inner_.on_epoch(epoch, step); }
  void set_schedules(LidarNerfModel& model, long step) override {
    inner_.set_schedules(model, step);
  }
  void step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed, long step,
            float lr) override {
    inner_.step(model, optim, seed, step, lr);
  }
  Json log_fields() override;
  std::string progress_text() override;
  NamedArrays state() const override;
  void load_state(const Checkpoint& ck, LidarNerfModel& model) override;

  ConsistencyLoss& loss() { return loss_; }
  ConsistencyTerm& term() { return loss_.term(); }
  std::pair<int, int> pair_at(uint64_t seed, long step) const { return loss_.pair_at(seed, step); }
  long steps_taken() const { return loss_.steps_taken(); }
  double seconds() const { return loss_.seconds(); }

 private:
  StepPolicy& inner_;
  ConsistencyLoss& loss_;
};

}  // namespace sgnlf::pipeline
