// TrainConfig: JSON reading (strict), writing, validation and hashing.
#include "pipeline/train_config.hpp"

#include <algorithm>
#include <cmath>

#include "pipeline/methods/registry.hpp"

namespace sgnlf::pipeline {

void FieldSizes::validate(const std::string& w) const {
  check_range(w, "levels", levels, 1, 32);
  check_range(w, "features_per_level", features_per_level, 1, 8);
  check_range(w, "log2_table_size", log2_table_size, 8, 24);
  check_range(w, "base_resolution", base_resolution, 2, 4096);
  check_range(w, "per_level_scale", per_level_scale, 1.0, 4.0);
  check_range(w, "density_hidden", density_hidden, 8, 256);
  check_range(w, "geo_features", geo_features, 1, 63);
  check_range(w, "head_hidden", head_hidden, 8, 256);
  check_range(w, "head_layers", head_layers, 1, 8);
  check_range(w, "dir_frequencies", dir_frequencies, 0, 16);
}

void OptimConfig::validate(const std::string& w) const {
  check_range(w, "lr", lr, 1e-8, 1e6);
  check_range(w, "beta1", beta1, 0.0, 0.999999);
  check_range(w, "beta2", beta2, 0.0, 0.999999999);
  check_range(w, "eps", eps, 1e-30, 1.0);
  check_range(w, "final_factor", final_factor, 1e-6, 1.0);
}

double OptimConfig::lr_at(long step, long iterations) const {
  const double t = iterations > 0 ? double(step) / double(iterations) : 0.0;
  return lr * std::pow(final_factor, std::min(1.0, std::max(0.0, t)));
}

void ScheduleConfig::validate(const std::string& w) const {
  check_range(w, "iterations", iterations, 1L, 100000000L);
  check_range(w, "rays_per_batch", rays_per_batch, 1, 1 << 20);
  check_range(w, "eval_every", eval_every, 0L, 100000000L);
  check_range(w, "checkpoint_every", checkpoint_every, 0L, 100000000L);
  check_range(w, "log_every", log_every, 1L, 100000000L);
  check_range(w, "divergence_factor", divergence_factor, 1.0, 1e30);
  check_range(w, "render_chunk_rays", render_chunk_rays, 64, 1 << 22);
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
  if (consistency) {
    consistency->validate(w);
    const long rays = long(consistency->render_rows) * consistency->render_cols;
    const long capacity = std::max(schedule.rays_per_batch, schedule.render_chunk_rays);
    if (consistency->enabled && rays > capacity)
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
uint64_t TrainConfig::hash() const {
  constexpr int kHashedThreads = 2;
  TrainConfig h = *this;
  if (h.pose_free) h.pose_free->geometric.threads = kHashedThreads;
  if (h.pose_graph) h.pose_graph->graph.threads = kHashedThreads;
  return fnv1a64(train_config_to_json(h).dump());
}

TrainConfig train_config_from_json(const Json& j, const std::string& where) {
  TrainConfig c;
  ConfigReader r(j, where);
  r.get("method", c.method).get("preset", c.preset);
  {
    auto f = r.child("field");
    f.get("levels", c.field.levels).get("features_per_level", c.field.features_per_level);
    f.get("log2_table_size", c.field.log2_table_size).get("base_resolution", c.field.base_resolution);
    f.get("per_level_scale", c.field.per_level_scale).get("density_hidden", c.field.density_hidden);
    f.get("geo_features", c.field.geo_features).get("head_hidden", c.field.head_hidden);
    f.get("head_layers", c.field.head_layers).get("dir_frequencies", c.field.dir_frequencies);
    f.finish();
  }
  if (r.has("render")) {
    Json rj;
    r.get("render", rj);
    c.render = render::RenderConfig::from_json(rj, where + ".render", c.render);
  }
  {
    auto o = r.child("optim");
    o.get("lr", c.optim.lr).get("beta1", c.optim.beta1).get("beta2", c.optim.beta2);
    o.get("eps", c.optim.eps).get("final_factor", c.optim.final_factor);
    o.finish();
  }
  {
    auto s = r.child("schedule");
    s.get("iterations", c.schedule.iterations).get("rays_per_batch", c.schedule.rays_per_batch);
    s.get("eval_every", c.schedule.eval_every).get("checkpoint_every", c.schedule.checkpoint_every);
    s.get("log_every", c.schedule.log_every).get("divergence_factor", c.schedule.divergence_factor);
    s.get("render_chunk_rays", c.schedule.render_chunk_rays);
    s.get("patches_on_even_epochs", c.schedule.patches_on_even_epochs);
    s.finish();
  }
  // The method's own sections (methods/method.hpp); ConfigError for an unknown method.
  const ConfigSections& sections = find_method(c.method).sections;
  if (sections.pose_free) c.pose_free = PoseFreeConfig::from_json(r);
  if (sections.spectral) c.spectral = SpectralFieldConfig::from_json(r);
  if (sections.pose_graph) c.pose_graph = PoseGraphConfig::from_json(r);
  if (sections.consistency) c.consistency = ConsistencyConfig::from_json(r);
  r.finish();
  c.validate();
  return c;
}

Json train_config_to_json(const TrainConfig& c) {
  Json j{
      {"method", c.method},
      {"preset", c.preset},
      {"field",
       {{"levels", c.field.levels},
        {"features_per_level", c.field.features_per_level},
        {"log2_table_size", c.field.log2_table_size},
        {"base_resolution", c.field.base_resolution},
        {"per_level_scale", c.field.per_level_scale},
        {"density_hidden", c.field.density_hidden},
        {"geo_features", c.field.geo_features},
        {"head_hidden", c.field.head_hidden},
        {"head_layers", c.field.head_layers},
        {"dir_frequencies", c.field.dir_frequencies}}},
      {"render", c.render.to_json()},
      {"optim",
       {{"lr", c.optim.lr},
        {"beta1", c.optim.beta1},
        {"beta2", c.optim.beta2},
        {"eps", c.optim.eps},
        {"final_factor", c.optim.final_factor}}},
      {"schedule",
       {{"iterations", c.schedule.iterations},
        {"rays_per_batch", c.schedule.rays_per_batch},
        {"eval_every", c.schedule.eval_every},
        {"checkpoint_every", c.schedule.checkpoint_every},
        {"log_every", c.schedule.log_every},
        {"divergence_factor", c.schedule.divergence_factor},
        {"render_chunk_rays", c.schedule.render_chunk_rays},
        {"patches_on_even_epochs", c.schedule.patches_on_even_epochs}}}};
  if (c.pose_free) c.pose_free->to_json(j);
  if (c.spectral) c.spectral->to_json(j);
  if (c.pose_graph) c.pose_graph->to_json(j);
  if (c.consistency) c.consistency->to_json(j);
  return j;
}

Json merge_config_json(Json base, const Json& overrides) {
  if (!overrides.is_object()) throw ConfigError("config overrides: expected a JSON object");
  for (auto it = overrides.begin(); it != overrides.end(); ++it) {
    if (it.value().is_object() && base.contains(it.key()) && base[it.key()].is_object())
      base[it.key()] = merge_config_json(base[it.key()], it.value());
    else
      base[it.key()] = it.value();
  }
  return base;
}

}  // namespace sgnlf::pipeline
