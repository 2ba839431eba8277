// TrainConfig: JSON reading (strict), writing, validation and hashing.
#include "pipeline/config/train_config.hpp"

#include <algorithm>
#include <cmath>

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "pipeline/methods/registry.hpp"

namespace sgnlf::pipeline {

void FieldSizes::validate(const std::string& where) const {
  config::check_fields(*this, where);
  grid.validate(where + ".grid");
}
void OptimConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  adam.validate(where + ".adam");
}
void ScheduleConfig::validate(const std::string& where) const { config::check_fields(*this, where); }

double OptimConfig::lr_at(long step, long iterations) const {
  const double t = iterations > 0 ? double(step) / double(iterations) : 0.0;
  return lr * std::pow(final_factor, std::min(1.0, std::max(0.0, t)));
}

void TrainConfig::validate() const {
  const std::string w = "config";
  std::string trainable;
  for (const auto& m : method_registry())
    if (m.implemented) trainable += (trainable.empty() ? "" : ", ") + m.name;
  const Method* spec = nullptr;
  for (const auto& m : method_registry())
    if (m.name == method && m.implemented) spec = &m;
  if (!spec)
    throw ConfigError(w + ": 'method' = \"" + method + "\" is not a trainable method (" +
                      trainable + ")");
  if (pose_free) pose_free->validate(w);
  if (spectral) spectral->validate(w);
  if (pose_graph) pose_graph->validate(w);
  if (lidar4d) lidar4d->validate(w);
  if (consistency) {
    consistency->validate(w);
    const long rays = long(consistency->render_rows) * consistency->render_cols;
    const long capacity = std::max(schedule.rays_per_batch, schedule.render_chunk_rays);
    if (rays > capacity)
      throw ConfigError(w + ".consistency: the render grid render_rows × render_cols = " +
                        std::to_string(rays) + " rays exceeds the model's ray capacity " +
                        std::to_string(capacity) +
                        " (the larger of schedule.rays_per_batch and render_chunk_rays)");
  }
  field.validate(w + ".field");
  render.validate(w + ".render");
  optim.validate(w + ".optim");
  schedule.validate(w + ".schedule");
  const int patch = render.patch_rows * render.patch_cols;
  if (render.weights.grad > 0 && schedule.rays_per_batch % patch != 0)
    throw ConfigError(w + ".schedule: 'rays_per_batch' = " + std::to_string(schedule.rays_per_batch) +
                      " is not a multiple of the patch size " + std::to_string(patch));
}

// Thread counts change no number (the pose graph's pair matching and the geometric stage's
// direction terms give identical results for any count), so the hash counts them at 2, the
// count every committed result was made with: its hash stays, a run resumes on a machine with
// other cores, and a preset may set them for its machine (run.json still records them).
uint64_t config_json_hash(Json j) {
  constexpr int kHashedThreads = 2;
  if (j.contains("geometric") && j["geometric"].contains("optimizer") &&
      j["geometric"]["optimizer"].contains("threads"))
    j["geometric"]["optimizer"]["threads"] = kHashedThreads;
  if (j.contains("pose_graph") && j["pose_graph"].contains("threads"))
    j["pose_graph"]["threads"] = kHashedThreads;
  return fnv1a64(j.dump());
}

uint64_t TrainConfig::hash() const { return config_json_hash(train_config_to_json(*this)); }

TrainConfig train_config_from_json(const Json& j, const std::string& where) {
  TrainConfig c;
  ConfigReader r(j, where);
  r.get("method", c.method).get("preset", c.preset);
  config::read_fields(r, "field", c.field);
  if (r.has("render")) {
    Json rj;
    r.get("render", rj);
    c.render = render::RenderConfig::from_json(rj, where + ".render", c.render);
  }
  config::read_fields(r, "optim", c.optim);
  config::read_fields(r, "schedule", c.schedule);
  // The method's own sections (methods/method.hpp); ConfigError for an unknown method.
  const ConfigSections& sections = find_method(c.method).sections;
  // pose_free's keys are the method's; the other sections are on exactly when present.
  if (sections.pose_free) c.pose_free = PoseFreeConfig::from_json(r);
  if (sections.spectral && r.has("spectral")) c.spectral = SpectralFieldConfig::from_json(r);
  if (sections.pose_graph && r.has("pose_graph")) c.pose_graph = PoseGraphConfig::from_json(r);
  if (sections.consistency && r.has("consistency"))
    c.consistency = ConsistencyConfig::from_json(r);
  if (sections.lidar4d && r.has("lidar4d")) c.lidar4d = Lidar4DConfig::from_json(r);
  r.finish();
  c.validate();
  return c;
}

Json train_config_to_json(const TrainConfig& c) {
  Json j{{"method", c.method},
         {"preset", c.preset},
         {"field", config::write_fields(c.field)},
         {"render", c.render.to_json()},
         {"optim", config::write_fields(c.optim)},
         {"schedule", config::write_fields(c.schedule)}};
  if (c.pose_free) c.pose_free->to_json(j);
  if (c.spectral) c.spectral->to_json(j);
  if (c.pose_graph) c.pose_graph->to_json(j);
  if (c.consistency) c.consistency->to_json(j);
  if (c.lidar4d) c.lidar4d->to_json(j);
  return j;
}

Json train_config_schema() {
  Json pose_graph = config::describe_fields<posegraph::ConfidenceGraphConfig>();
  pose_graph.update(config::describe_fields<PoseGraphConfig>());  // one object, as written
  Json j{{"field", config::describe_fields<FieldSizes>()},
         {"render", config::describe_fields<render::RenderConfig>()},
         {"optim", config::describe_fields<OptimConfig>()},
         {"schedule", config::describe_fields<ScheduleConfig>()},
         {"spectral", config::describe_fields<SpectralFieldConfig>()},
         {"pose_graph", pose_graph},
         {"consistency", config::describe_fields<ConsistencyConfig>()},
         {"lidar4d", config::describe_fields<Lidar4DConfig>()}};
  j.update(config::describe_fields<PoseFreeConfig>());  // poses, pose_optim, ..., geometric
  return j;
}

Json drop_removed_keys(Json j) {
  if (!j.is_object()) return j;
  for (auto it = j.begin(); it != j.end();) {
    if (it.value().is_null()) {
      it = j.erase(it);
    } else {
      it.value() = drop_removed_keys(it.value());
      ++it;
    }
  }
  return j;
}

Json merge_config_json(Json base, const Json& overrides) {
  if (!overrides.is_object()) throw ConfigError("config overrides: expected a JSON object");
  for (auto it = overrides.begin(); it != overrides.end(); ++it) {
    if (it.value().is_null())
      base[it.key()] = nullptr;  // a removal, kept so that merged overrides still remove
    else if (it.value().is_object())  // onto the base's object, or a new one
      base[it.key()] = merge_config_json(
          base.contains(it.key()) && base[it.key()].is_object() ? base[it.key()] : Json::object(),
          it.value());
    else
      base[it.key()] = it.value();
  }
  return base;
}

}  // namespace sgnlf::pipeline
