// SpectralSchedule (spectral_schedule.hpp).
#include "pipeline/train/spectral_schedule.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "posegraph/frame_cloud.hpp"
#include "spectral/point_cloud_surface.hpp"

namespace sgnlf::pipeline {
namespace {

constexpr uint32_t kPoolStream = 0x5e1f;   // thinning of the pool, + epoch
constexpr uint32_t kBatchStream = 0x5e2f;  // batch draws (keyed by step)

std::vector<double> pose_doubles(const std::vector<Pose>& T) {
  std::vector<double> v;
  v.reserve(T.size() * 12);
  for (const auto& p : T)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) v.push_back(p.matrix()(r, c));
  return v;
}

std::vector<Pose> poses_from_doubles(const std::vector<double>& v) {
  std::vector<Pose> T(v.size() / 12, Pose::Identity());
  for (size_t k = 0; k < T.size(); ++k)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) T[k].matrix()(r, c) = v[12 * k + size_t(4 * r + c)];
  return T;
}

}  // namespace

SpectralLoss::SpectralLoss(cl::Runtime& rt, size_t psi_params, const TrainConfig& cfg,
                           SurfacePoolSource source, uint64_t seed)
    : cfg_(cfg), source_(std::move(source)), seed_(seed), psi_params_(psi_params),
      psi_adam_(rt, psi_params) {
  require(!source_.frames.empty() && source_.frames.size() == source_.points_lidar.size(),
          "SpectralLoss: the surface pool source needs one point set per frame (" +
              std::to_string(source_.frames.size()) + " frames, " +
              std::to_string(source_.points_lidar.size()) + " point sets)");
}

void SpectralLoss::build_pool(long epoch, const std::vector<Pose>& T_norm) {
  const auto t0 = std::chrono::steady_clock::now();
  const double s = source_.norm.scale;
  std::vector<Eigen::Vector3d> pts;
  for (size_t k = 0; k < source_.frames.size(); ++k) {
    const Pose& T = T_norm[k];
    for (const auto& p : source_.points_lidar[k]) pts.push_back(T * (p.cast<double>() * s));
  }
  Rng rng(seed_, kPoolStream + uint32_t(epoch));
  spectral::PointCloudSurfaceStats st;
  pool_ = spectral::surface_from_points(pts, cfg_.spectral->radius_m * s, rng, &st);
  if (pool_.size() < size_t(cfg_.spectral->batch) / 4)
    throw NumericError("spectral embedding: the surface pool of epoch " + std::to_string(epoch) +
                       " kept " + std::to_string(pool_.size()) + " of " +
                       std::to_string(st.input) + " observed points (radius_m " +
                       std::to_string(cfg_.spectral->radius_m) + " too small for the scans?)");
  pool_poses_ = T_norm;
  pool_epoch_ = epoch;
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void SpectralLoss::take_own_step(OwnGroupStep& group) {
  const long step = group.step;
  if (step % cfg_.spectral->every != 0) return;
  if (pool_.empty()) throw Error("SpectralLoss: no surface pool (SpectralSchedule::on_epoch not called)");
  const auto t0 = std::chrono::steady_clock::now();
  Rng rng(seed_ ^ (group.seed * 0x9E3779B97F4A7C15ull) ^ (uint64_t(step) * 0xD1B54A32D192ED03ull),
          kBatchStream);
  std::vector<spectral::SurfacePoint> batch(size_t(cfg_.spectral->batch));
  for (auto& p : batch) {
    p = pool_[size_t(rng.next_u64() % pool_.size())];
    p.w = 1.0 / double(batch.size());
  }
  last_loss_ = group.spectral_gradient(batch);
  const OwnGroupStep::Group psi = group.psi();
  require(psi.count == psi_params_, "SpectralLoss: the model's Psi has " + std::to_string(psi.count) +
                                        " parameters, its optimiser " + std::to_string(psi_params_));
  psi_adam_.begin_step();
  psi_adam_.update(psi.params, psi.grad, 0, psi.count,
                   float(cfg_.spectral->lr_at(step, cfg_.schedule.iterations)));
  if (!std::isfinite(last_loss_))
    throw NumericError("spectral embedding: loss not finite at step " + std::to_string(step));
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void SpectralLoss::report(LossReport& r, const std::vector<float>&) const {
  r.add("spectral", last_loss_, /*in_total=*/false);
}

NamedArrays SpectralLoss::optimizer_state() const {
  NamedArrays a;
  a.emplace_back("spectral.psi.adam_m", psi_adam_.m().read_vec<float>(psi_params_));
  a.emplace_back("spectral.psi.adam_v", psi_adam_.v().read_vec<float>(psi_params_));
  a.emplace_back("spectral.psi.adam_t", pack_doubles({double(psi_adam_.step())}));
  return a;
}

NamedArrays SpectralLoss::state() const {
  NamedArrays a;
  a.emplace_back("spectral.pool_epoch", pack_doubles({double(pool_epoch_)}));
  a.emplace_back("spectral.pool_poses", pack_doubles(pose_doubles(pool_poses_)));
  a.emplace_back("spectral.last_loss", pack_doubles({last_loss_}));
  return a;
}

void SpectralLoss::load_state(const Checkpoint& ck) {
  const auto m = ck.array("spectral.psi.adam_m", psi_params_);
  const auto v = ck.array("spectral.psi.adam_v", psi_params_);
  const auto t = int64_t(unpack_doubles(ck.array("spectral.psi.adam_t", 2)).at(0));
  psi_adam_.reset();
  psi_adam_.m().write_vec(m);
  psi_adam_.v().write_vec(v);
  for (int64_t i = 0; i < t; ++i) psi_adam_.begin_step();  // Adam exposes no setter
  last_loss_ = unpack_doubles(ck.array("spectral.last_loss", 2)).at(0);
  const long epoch = long(unpack_doubles(ck.array("spectral.pool_epoch", 2)).at(0));
  pool_.clear();
  if (epoch >= 0) {
    const auto T = poses_from_doubles(
        unpack_doubles(ck.array("spectral.pool_poses", 24 * source_.frames.size())));
    build_pool(epoch, T);
  }
}

SpectralSchedule::SpectralSchedule(StepPolicy& inner, SpectralLoss& loss,
                                   const LidarNerfModel& model, const TrainConfig& cfg,
                                   PoseOf pose_of)
    : inner_(inner), loss_(loss), model_(model), cfg_(cfg), pose_of_(std::move(pose_of)) {
  require(model.hybrid(), "SpectralSchedule: the model has no hybrid spectral-geometric encoder");
}

void SpectralSchedule::on_epoch(long epoch, long step) {
  inner_.on_epoch(epoch, step);
  std::vector<Pose> T(loss_.frames().size());
  for (size_t k = 0; k < T.size(); ++k) T[k] = pose_of_(loss_.frames()[k]);
  loss_.build_pool(epoch, T);
}

void SpectralSchedule::set_schedules(LidarNerfModel& model, long step) {
  inner_.set_schedules(model, step);
  model.set_fusion_weight(float(cfg_.spectral->fusion.lambda(int(step))));
}

void SpectralSchedule::step(LidarNerfModel& model, FieldOptimizer& optim, uint64_t seed,
                            long step, float lr) {
  inner_.step(model, optim, seed, step, lr);
}

Json SpectralSchedule::log_fields() {
  Json j = inner_.log_fields();
  j["lambda"] = model_.fusion_weight();
  j["surface_points"] = loss_.pool_size();
  return j;
}

std::string SpectralSchedule::progress_text() {
  char buf[48];
  std::snprintf(buf, sizeof buf, " Lspe %.3g", loss_.last_loss());
  return inner_.progress_text() + buf;
}

NamedArrays SpectralSchedule::state() const {
  NamedArrays a = inner_.state();
  a.emplace_back("spectral.psi.params", model_.read_psi());
  for (auto& x : loss_.optimizer_state()) a.push_back(std::move(x));
  for (auto& x : loss_.state()) a.push_back(std::move(x));
  return a;
}

void SpectralSchedule::load_state(const Checkpoint& ck, LidarNerfModel& model) {
  inner_.load_state(ck, model);
  restore_hybrid_encoder(model, cfg_, ck);  // Ψ (and λ, which the trainer sets again)
  loss_.load_state(ck);                     // Ψ's optimiser, the pool
}

void restore_hybrid_encoder(LidarNerfModel& model, const TrainConfig& cfg, const Checkpoint& ck) {
  if (!cfg.hybrid_encoder()) return;
  model.write_psi(ck.array("spectral.psi.params", model.psi_params()));
  model.set_fusion_weight(float(cfg.spectral->fusion.lambda(int(std::max(0L, ck.step - 1)))));
}

SurfacePoolSource make_surface_pool_source(const Dataset& d, const Scene& scene,
                                           int points_per_frame, uint64_t seed) {
  SurfacePoolSource src;
  src.norm = scene.norm;
  for (int f : scene.train) {
    bool pose_only = false;
    for (int q : scene.pose_only) pose_only = pose_only || q == f;
    if (pose_only) continue;
    std::vector<Eigen::Vector3f> pts;
    for (const auto& p : posegraph::subsample_points(d.frames[size_t(f)].points,
                                                     size_t(points_per_frame), seed, uint32_t(f)))
      pts.push_back(p);
    src.frames.push_back(f);
    src.points_lidar.push_back(std::move(pts));
  }
  return src;
}

}  // namespace sgnlf::pipeline
