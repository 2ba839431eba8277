// ConsistencySchedule (consistency_schedule.hpp).
#include "pipeline/train/consistency_schedule.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"
#include "pipeline/model/ray_batch.hpp"

namespace sgnlf::pipeline {
namespace {

constexpr uint32_t kPairStream = 0xc0a5;  // partner draw, keyed by (seed, step)

}  // namespace

ConsistencyLoss::ConsistencyLoss(cl::Runtime& rt, const Scene& scene, const TrainConfig& cfg,
                                 PoseSet& poses, int max_rays, uint64_t seed)
    : scene_(scene),
      cfg_(cfg),
      poses_(poses),
      seed_(seed),
      term_(rt, scene, *cfg.consistency, max_rays) {
  require(poses.size() == scene.T_world_lidar.size(),
          "ConsistencyLoss: " + std::to_string(poses.size()) + " poses for " +
              std::to_string(scene.T_world_lidar.size()) + " frames");
}

bool ConsistencyLoss::trainable(int f) const {
  return std::find(scene_.train.begin(), scene_.train.end(), f) != scene_.train.end() &&
         std::find(scene_.pose_only.begin(), scene_.pose_only.end(), f) == scene_.pose_only.end();
}

std::pair<int, int> ConsistencyLoss::pair_at(uint64_t seed, long step) const {
  const int i = batch_frame(scene_, seed, step);
  if (!trainable(i)) return {-1, -1};
  std::vector<int> partners;
  for (int o : cfg_.consistency->offsets)
    for (int j : {i + o, i - o})
      if (trainable(j)) partners.push_back(j);
  if (partners.empty()) return {-1, -1};
  Rng rng(seed_ ^ (seed * 0x9E3779B97F4A7C15ull) ^ (uint64_t(step) * 0xD1B54A32D192ED03ull),
          kPairStream);
  return {i, partners[rng.below(uint32_t(partners.size()))]};
}

void ConsistencyLoss::add_field_gradient(FieldPass& field) {
  const long step = field.step;
  if (!cfg_.consistency->active_at(step)) return;
  const auto [i, j] = pair_at(field.seed, step);
  if (i < 0) return;
  const auto t0 = std::chrono::steady_clock::now();
  ConsistencyPair p;
  p.i = i, p.j = j;
  p.T_init_i = poses_.initial(size_t(i)), p.xi_i = poses_.correction(size_t(i));
  p.T_init_j = poses_.initial(size_t(j)), p.xi_j = poses_.correction(size_t(j));
  const bool optimize = cfg_.pose_free->pose_optim.optimize;
  last_ = term_.run(field, p, true, optimize);
  if (optimize) {
    poses_.add_pending(size_t(i), last_.grad_xi_i);
    poses_.add_pending(size_t(j), last_.grad_xi_j);
  }
  last_i_ = i, last_j_ = j, last_step_ = step;
  ++steps_;
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void ConsistencyLoss::report(LossReport& r, const std::vector<float>&) const {
  r.add("consistency", cfg_.consistency->weight * last_.l_con, false);
}

Json ConsistencyLoss::log_fields() const {
  if (last_step_ < 0) return Json();
  return Json{{"l_d", last_.l_d},
              {"l_con", last_.l_con},
              {"d_real", last_.d_real_mean},
              {"d_fake", last_.d_fake_mean},
              {"coverage", last_.coverage},
              {"rendered_points", last_.rendered_points},
              {"pair", {last_i_, last_j_}},
              {"step", last_step_},
              {"steps", steps_}};
}

Json ConsistencySchedule::log_fields() {
  Json j = inner_.log_fields();
  Json c = loss_.log_fields();
  if (!c.is_null()) j["consistency"] = std::move(c);
  return j;
}

std::string ConsistencySchedule::progress_text() {
  if (loss_.log_fields().is_null()) return inner_.progress_text();
  char buf[64];
  std::snprintf(buf, sizeof buf, " LD %.3g Lcon %.3g", loss_.last().l_d, loss_.last().l_con);
  return inner_.progress_text() + buf;
}

NamedArrays ConsistencySchedule::state() const {
  NamedArrays a = inner_.state();
  for (auto& x : loss_.state()) a.push_back(std::move(x));
  return a;
}

void ConsistencySchedule::load_state(const Checkpoint& ck, LidarNerfModel& model) {
  inner_.load_state(ck, model);
  loss_.load_state(ck);
}

NamedArrays ConsistencyLoss::state() const {
  NamedArrays a;
  // Reads only: PatchDiscriminator has no const accessors for its buffers and Adam.
  auto& disc = const_cast<ConsistencyTerm&>(term_).discriminator();
  const size_t n = disc.n_params();
  a.emplace_back("consistency.disc.params", disc.params().read_vec<float>(n));
  a.emplace_back("consistency.disc.adam_m", disc.adam().m().read_vec<float>(n));
  a.emplace_back("consistency.disc.adam_v", disc.adam().v().read_vec<float>(n));
  a.emplace_back("consistency.disc.adam_t", pack_doubles({double(disc.adam().step())}));
  a.emplace_back("consistency.pose_pending", pack_doubles(poses_.pending_flat()));
  a.emplace_back("consistency.last",
                 pack_doubles({last_.l_d, last_.l_con, last_.d_real_mean, last_.d_fake_mean,
                               last_.coverage, double(last_.rendered_points), double(last_i_),
                               double(last_j_), double(last_step_), double(steps_)}));
  return a;
}

void ConsistencyLoss::load_state(const Checkpoint& ck) {
  auto& disc = term_.discriminator();
  const size_t n = disc.n_params();
  disc.params().write_vec(ck.array("consistency.disc.params", n));
  disc.adam().reset();
  disc.adam().m().write_vec(ck.array("consistency.disc.adam_m", n));
  disc.adam().v().write_vec(ck.array("consistency.disc.adam_v", n));
  const long t = long(unpack_doubles(ck.array("consistency.disc.adam_t", 2)).at(0));
  for (long k = 0; k < t; ++k) disc.adam().begin_step();  // Adam exposes no setter
  poses_.set_pending_flat(unpack_doubles(ck.array("consistency.pose_pending", 14 * poses_.size())));
  const auto v = unpack_doubles(ck.array("consistency.last", 20));
  last_.l_d = v[0], last_.l_con = v[1], last_.d_real_mean = v[2], last_.d_fake_mean = v[3];
  last_.coverage = v[4], last_.rendered_points = int(v[5]);
  last_i_ = int(v[6]), last_j_ = int(v[7]), last_step_ = long(v[8]), steps_ = long(v[9]);
}

}  // namespace sgnlf::pipeline
