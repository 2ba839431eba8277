// The training loop (see trainer.hpp).
#include "pipeline/train/trainer.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "pipeline/train/field_optimizer.hpp"
#include "pipeline/model/ray_batch.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;

std::string checkpoint_path(const std::string& run_dir) {
  return (fs::path(run_dir) / "checkpoints" / "latest.ckpt").string();
}

Json loss_json(const LossReport& l) {
  Json j{{"total", l.total()}};
  for (const LossRecord& r : l.records()) j[r.name] = r.value;
  return j;
}

namespace {

void append_line(const std::string& path, const Json& j) {
  std::ofstream out(path, std::ios::app);
  if (!out) throw IoError(path + ": cannot open for appending");
  out << j.dump() << "\n";
}

// Keeps the lines of a JSON-lines log whose "step" is below `limit` (at most `limit` when
// `inclusive`), dropping the rest and any torn last line: after a crash and resume the log
// continues from the checkpoint's step instead of repeating the steps after it.
void truncate_log(const std::string& path, long limit, bool inclusive) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return;
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot open to continue the log after resuming");
  std::string kept, line;
  size_t dropped = 0;
  while (std::getline(in, line)) {
    const Json j = Json::parse(line, nullptr, /*allow_exceptions=*/false);
    const auto it = j.is_object() ? j.find("step") : j.end();
    const bool keep = it != j.end() && it->is_number_integer() &&
                      (inclusive ? it->get<long>() <= limit : it->get<long>() < limit);
    if (keep)
      kept += line + "\n";
    else
      ++dropped;
  }
  if (dropped == 0) return;
  write_text_file(path, kept);
  log::info(path, ": dropped ", dropped, " lines past step ", limit, " (written before the resumed checkpoint)");
}

// Smoothed-loss divergence tracker (state kept in checkpoints).
struct Tracker {
  double best = 0.0, smoothed = 0.0;
  void add(double loss) {
    smoothed = smoothed == 0.0 ? loss : 0.9 * smoothed + 0.1 * loss;
    best = best == 0.0 ? smoothed : std::min(best, smoothed);
  }
};

bool all_finite(const std::vector<float>& v) {
  for (float x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

}  // namespace

TrainSummary train(LidarNerfModel& model, const Scene& scene, const TrainConfig& cfg,
                   const TrainOptions& opt) {
  require(!opt.run_dir.empty(), "train: run_dir is required");
  fs::create_directories(fs::path(opt.run_dir) / "checkpoints");
  const std::string ck_path = checkpoint_path(opt.run_dir);
  const std::string log_path = (fs::path(opt.run_dir) / "train_log.jsonl").string();
  const std::string eval_path = (fs::path(opt.run_dir) / "eval_log.jsonl").string();
  const uint64_t hash = cfg.hash();
  const long total = cfg.schedule.iterations;

  GroundTruthPoseStep gt_step(scene, cfg);
  StepPolicy& policy = opt.policy ? *opt.policy : gt_step;
  FieldOptimizer optim(model, cfg);  // zero moments; a resume loads the checkpoint's
  TrainSummary sum;
  Tracker tracker;
  long last_good = -1;
  if (opt.resume && have_checkpoint(ck_path)) {
    std::string used;
    const Checkpoint ck = load_latest_checkpoint(ck_path, hash, opt.seed, &used);
    model.set_params(ck.array("params", model.n_params()));
    optim.set_state({ck.array("adam_m", model.n_params()), ck.array("adam_v", model.n_params()),
                     ck.step});
    if (opt.policy) {
      opt.policy->load_state(ck, model);
      if (ck.step > 0) opt.policy->set_schedules(model, ck.step - 1);  // as the last step left them
    }
    tracker.best = ck.best_loss;
    tracker.smoothed = ck.smoothed_loss;
    sum.start_step = last_good = ck.step;
    log::info("resuming ", opt.run_dir, " from step ", ck.step, " (", used, ")");
  } else {
    model.init_params(opt.seed);
  }
  // The logs hold exactly the steps up to the state training continues from (none when it
  // starts afresh); the geometric log is keyed by the step its epoch starts at, rerun on resume.
  truncate_log(log_path, sum.start_step, true);
  truncate_log(eval_path, sum.start_step, true);
  truncate_log((fs::path(opt.run_dir) / "geometric_log.jsonl").string(), sum.start_step, false);

  auto save = [&](long step) {
    std::vector<float> params = model.params();
    OptimizerState adam = optim.state();
    if (!all_finite(params) || !all_finite(adam.m) || !all_finite(adam.v))
      throw NumericError("training diverged at step " + std::to_string(step) +
                         ": non-finite parameters; the last good checkpoint (step " +
                         std::to_string(last_good) + ") is kept at " + ck_path);
    Checkpoint ck;
    ck.step = step;
    ck.seed = opt.seed;
    ck.config_hash = hash;
    ck.best_loss = tracker.best;
    ck.smoothed_loss = tracker.smoothed;
    ck.arrays = {{"params", std::move(params)}, {"adam_m", std::move(adam.m)},
                 {"adam_v", std::move(adam.v)}};
    for (auto& a : policy.state()) ck.arrays.push_back(std::move(a));
    save_checkpoint_rotating(ck_path, ck);
    last_good = step;
  };

  const long end = opt.stop_at >= 0 ? std::min(opt.stop_at, total) : total;
  const long samples_per_step =
      long(cfg.schedule.rays_per_batch) * (cfg.render.n_samples + cfg.render.n_importance);
  // The line counts to the step this process stops at (--stop-at), and its rate only the steps
  // this process ran (a resumed run starts at its checkpoint's step).
  Progress progress("train " + cfg.method + "-" + cfg.preset, end, 10.0, sum.start_step);
  if (opt.show_progress && end < total)
    log::info("training steps ", sum.start_step, " to ", end, " of ", total, " (stop at step ",
              end, "; resumable)");
  const auto t0 = std::chrono::steady_clock::now();
  // The first step of a fresh run is logged; a resumed run logs exactly the steps the
  // uninterrupted run logs, so that its train_log.jsonl reads the same.
  bool first = true;
  const bool log_first = sum.start_step == 0;
  double live_sum = 0.0, eval_s = 0.0;
  const long epoch_len = long(scene.train.size());
  for (long step = sum.start_step; step < end; ++step) {
    if (step % epoch_len == 0) {
      policy.on_epoch(step / epoch_len, step);
      // The first epoch's start (the coarse geometric alignment of the pose-free methods) is
      // not the steps' time: the ETA starts with the first step.
      if (step == sum.start_step) progress.restart_clock(step);
    }
    const float lr = float(cfg.optim.lr_at(step, total));
    policy.set_schedules(model, step);
    policy.step(model, optim, opt.seed, step, lr);
    const double live = double(model.live_samples()) / double(samples_per_step);
    live_sum += live;
    const long done = step + 1;
    fault_point("after-step", done);
    const bool ck_due = (cfg.schedule.checkpoint_every > 0 && done % cfg.schedule.checkpoint_every == 0) ||
                        done == end;
    const bool eval_due = cfg.schedule.eval_every > 0 && done % cfg.schedule.eval_every == 0 &&
                          opt.evaluate;
    if (done % cfg.schedule.log_every == 0 || ck_due || eval_due || (first && log_first)) {
      const LossReport loss = model.read_losses();  // waits for the step
      const double total_loss = loss.total();
      if (!std::isfinite(total_loss) || !loss.finite())
        throw NumericError("training diverged at step " + std::to_string(done) + ": loss = " +
                           std::to_string(total_loss) + " (lr " + std::to_string(lr) +
                           "); the last good checkpoint (step " + std::to_string(last_good) +
                           ") is kept at " + ck_path);
      tracker.add(total_loss);
      if (tracker.smoothed > cfg.schedule.divergence_factor * tracker.best)
        throw NumericError("training diverged at step " + std::to_string(done) +
                           ": smoothed loss " + std::to_string(tracker.smoothed) + " > " +
                           std::to_string(cfg.schedule.divergence_factor) + " x best " +
                           std::to_string(tracker.best) + "; the last good checkpoint (step " +
                           std::to_string(last_good) + ") is kept at " + ck_path);
      if (first) sum.first_loss = loss;
      first = false;
      sum.last_loss = loss;
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      Json line{{"step", done}, {"lr", lr}, {"elapsed_s", el}, {"live_fraction", live},
                {"loss", loss_json(loss)}};
      if (cfg.render.coarse_waves > 1)  // the coarse samples the waves evaluated
        line["coarse_fraction"] = double(model.coarse_evaluated()) /
                                  double(long(cfg.schedule.rays_per_batch) * cfg.render.n_samples);
      line.update(policy.log_fields());
      append_line(log_path, line);
      char extra[96];
      std::snprintf(extra, sizeof extra, "loss %.5f  lr %.2e", total_loss, double(lr));
      if (opt.show_progress) progress.update(done, extra + policy.progress_text());
      if (opt.on_progress) opt.on_progress(done, end, extra + policy.progress_text());
    }
    if (ck_due) save(done);
    if (eval_due) {
      // train_seconds: this session's wall time up to here without the evaluations (the
      // time-to-quality clock).
      const auto e0 = std::chrono::steady_clock::now();
      const double train_s = std::chrono::duration<double>(e0 - t0).count() - eval_s;
      Json m = opt.evaluate(done);
      eval_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - e0).count();
      append_line(eval_path, Json{{"step", done}, {"train_seconds", train_s}, {"metrics", std::move(m)}});
    }
  }
  sum.end_step = std::max(sum.start_step, end);
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const long ran = sum.end_step - sum.start_step;
  sum.steps_per_s = sum.seconds > 0 ? ran / sum.seconds : 0.0;
  sum.samples_per_s = sum.steps_per_s * double(samples_per_step);
  sum.live_fraction = ran > 0 ? live_sum / double(ran) : 1.0;
  sum.finished = sum.end_step >= total;
  // A finished run keeps one checkpoint: the fallback costs a model's worth of disk.
  if (sum.finished && last_good == total) {
    std::error_code ec;
    fs::remove(previous_checkpoint_path(ck_path), ec);
  }
  if (opt.show_progress) progress.finish("");
  return sum;
}

}  // namespace sgnlf::pipeline
