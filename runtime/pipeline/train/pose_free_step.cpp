// PoseFreeStep (see pose_free_step.hpp).
#include "pipeline/train/pose_free_step.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/config.hpp"
#include "core/error.hpp"
#include "field/hash_grid.hpp"
#include "metrics/evaluate.hpp"
#include "pipeline/model/ray_batch.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;

PoseFreeStep::PoseFreeStep(const Scene& scene, const TrainConfig& cfg, PoseSet& poses,
                           std::vector<Pose> gt, std::string run_dir, GeometricStage geometric)
    : scene_(scene),
      cfg_(cfg),
      poses_(poses),
      gt_(std::move(gt)),
      run_dir_(std::move(run_dir)),
      geometric_(std::move(geometric)),
      ema_(scene.T_world_lidar.size(), 0.0),
      seen_(scene.T_world_lidar.size(), 0.0) {
  require(poses.size() == scene.T_world_lidar.size(),
          "PoseFreeStep: " + std::to_string(poses.size()) + " poses for " +
              std::to_string(scene.T_world_lidar.size()) + " frames");
}

std::vector<Pose> PoseFreeStep::poses_world() const {
  std::vector<Pose> out;
  for (size_t i = 0; i < poses_.size(); ++i) out.push_back(denormalize_pose(poses_.pose(i), scene_.norm));
  return out;
}

Json PoseFreeStep::pose_errors() const {
  if (gt_.size() < 2) return Json::object();
  return metrics::pose_metrics(poses_world(), gt_, reference_);
}

void PoseFreeStep::on_epoch(long epoch, long step) {
  if (!geometric_) return;
  const double progress = double(step) / double(cfg_.schedule.iterations);
  const Json before = pose_errors();
  const auto t0 = std::chrono::steady_clock::now();
  Json line = geometric_.run(poses_, epoch, progress, report_);
  if (line.is_null()) return;  // the stage did nothing this epoch
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  geometric_seconds_ += secs;
  line["seconds"] = secs;
  line["epoch"] = epoch;
  line["step"] = step;
  line["progress"] = progress;
  line["before"] = before;
  line["after"] = pose_errors();
  if (!run_dir_.empty()) {
    const std::string path = (fs::path(run_dir_) / "geometric_log.jsonl").string();
    std::ofstream out(path, std::ios::app);
    if (!out) throw IoError(path + ": cannot open for appending");
    out << line.dump() << "\n";
  }
}

double PoseFreeStep::reweight(int frame) const {
  if (!cfg_.reweighting()) return 1.0;
  const ReweightConfig& rc = *cfg_.pose_free->reweight;
  if (rc.fraction <= 0.0) return 1.0;
  std::vector<double> losses;
  for (int f : scene_.train) {
    if (seen_[size_t(f)] == 0.0) return 1.0;  // every frame seen once before ranking
    losses.push_back(ema_[size_t(f)]);
  }
  const size_t k = size_t(double(losses.size()) * rc.fraction);
  if (k == 0) return 1.0;
  std::nth_element(losses.begin(), losses.begin() + long(k - 1), losses.end(), std::greater<>());
  return ema_[size_t(frame)] >= losses[k - 1] ? rc.factor : 1.0;
}

void PoseFreeStep::set_schedules(LidarNerfModel& model, long step) {
  if (!cfg_.pose_free->coarse_to_fine) return;
  auto w = field::barf_level_weights(double(step) / double(cfg_.schedule.iterations), model.levels());
  if (w != level_w_) model.set_level_weights(level_w_ = std::move(w));
}

void PoseFreeStep::step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed, long step,
                        float lr) {
  const PoseFreeConfig& pc = *cfg_.pose_free;
  if (!grad_reader_) grad_reader_ = make_pose_grad_reader(model.runtime().device_profile().pose_grad);
  const double progress = double(step) / double(cfg_.schedule.iterations);
  const RayBatch b = draw_ray_batch(scene_, cfg_, seed, step, [&](int f) { return poses_.pose(size_t(f)); });
  const bool optimize = pc.pose_optim.optimize && step >= pc.pose_optim.start_step;
  const bool pose_only =
      std::find(scene_.pose_only.begin(), scene_.pose_only.end(), b.frame) != scene_.pose_only.end();
  const float lr_frame = pose_only ? 0.0f : float(lr * reweight(b.frame));
  model.forward_backward(b, seed, step, optimize);
  // No pose step: any pose gradient pending for the frame is void (a loss term's included).
  if (!optimize) poses_.drop_pending(size_t(b.frame));
  optim.step(lr_frame);
  if (pc.reweight) {
    const double l = grad_reader_->read_losses(model, optimize).total();
    double& e = ema_[size_t(b.frame)];
    e = seen_[size_t(b.frame)] == 0.0 ? l : pc.reweight->ema * e + (1.0 - pc.reweight->ema) * l;
    seen_[size_t(b.frame)] = 1.0;
  }
  if (!optimize) return;
  poses_.step(size_t(b.frame), grad_reader_->pose_gradient(model, scene_, poses_, b), progress);
}

Json PoseFreeStep::log_fields() {
  Json j = pose_errors();
  return j.empty() ? Json::object() : Json{{"pose", j}};
}

std::string PoseFreeStep::progress_text() {
  const Json e = pose_errors();
  if (e.empty()) return "";
  char buf[64];
  std::snprintf(buf, sizeof buf, "  ATE %.3f m (horizontal %.3f)", e.at("ate_m").get<double>(),
                e.at("ate_h_m").get<double>());
  return buf;
}

NamedArrays PoseFreeStep::state() const {
  NamedArrays a = poses_.state_arrays();
  a.push_back({"reweight.ema", pack_doubles(ema_)});
  a.push_back({"reweight.seen", pack_doubles(seen_)});
  if (geometric_.state)
    for (auto& x : geometric_.state()) a.push_back(std::move(x));
  return a;
}

void PoseFreeStep::load_state(const Checkpoint& ck, LidarNerfModel&) {
  poses_.load_state([&](const std::string& name, size_t n) { return ck.array(name, n); });
  ema_ = unpack_doubles(ck.array("reweight.ema", 2 * ema_.size()));
  seen_ = unpack_doubles(ck.array("reweight.seen", 2 * seen_.size()));
  if (geometric_.load_state) geometric_.load_state(ck);
}

}  // namespace sgnlf::pipeline
