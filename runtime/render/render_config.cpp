// RenderConfig presets, validation and JSON.
#include "core/config_fields.hpp"
#include "render/render_config.hpp"

#include "core/config.hpp"

#include <algorithm>
#include <cmath>

namespace sgnlf::render {

RenderConfig RenderConfig::preset(const std::string& dataset) {
  RenderConfig c;
  if (dataset == "kitti360") {
    c.weights = {1000.0f, 1.0f, 10.0f, 100.0f};
  } else if (dataset == "nuscenes") {
    c.weights = {1000.0f, 4.5f, 100.0f, 100.0f};
  } else {
    throw ConfigError("render preset: unknown dataset '" + dataset +
                      "' (expected kitti360 or nuscenes)");
  }
  return c;
}

void RenderConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
  check_range(where, "coarse_waves", coarse_waves, 1, n_samples);
  if (!(far_m > near_m))
    throw ConfigError(where + ": 'far_m' = " + std::to_string(far_m) +
                      " must exceed 'near_m' = " + std::to_string(near_m));
  if (eval_depth != "expected" && eval_depth != "median" && eval_depth != "mix")
    throw ConfigError(where + ": 'eval_depth' = '" + eval_depth +
                      "' (expected \"expected\", \"median\" or \"mix\")");
  if (head_weight_threshold > 0.0f && !(stop_transmittance > 0.0f))
    throw ConfigError(where + ": 'head_weight_threshold' = " +
                      std::to_string(head_weight_threshold) +
                      " needs early termination ('stop_transmittance' > 0)");
  if (coarse_waves > 1 && !(stop_transmittance > 0.0f))
    throw ConfigError(where + ": 'coarse_waves' = " + std::to_string(coarse_waves) +
                      " needs early termination ('stop_transmittance' > 0)");
  if (surface_band_end_m > surface_band_start_m)
    throw ConfigError(where + ": 'surface_band_end_m' = " + std::to_string(surface_band_end_m) +
                      " must not exceed 'surface_band_start_m' = " +
                      std::to_string(surface_band_start_m) + " (the band narrows)");
  if (patch_rows * patch_cols < 2)
    throw ConfigError(where + ": a patch of 'patch_rows' x 'patch_cols' = 1 x 1 has no pairs");
}

float RenderConfig::surface_band_m(long step) const {
  if (surface_anneal_steps <= 0 || step >= surface_anneal_steps) return surface_band_end_m;
  const double f = double(std::max(0L, step)) / double(surface_anneal_steps);
  return float(double(surface_band_start_m) *
               std::pow(double(surface_band_end_m) / double(surface_band_start_m), f));
}

std::string RenderConfig::sampler_name() const {
  if (!sampler.empty()) return sampler;
  if (stop_transmittance > 0.0f) return "terminated";
  return n_importance > 0 ? "importance" : "uniform";
}

std::string RenderConfig::training_sampler_name() const {
  if (!training_sampler.empty()) return training_sampler;
  return surface_sampling() ? "surface" : sampler_name();
}

RenderConfig RenderConfig::from_json(const Json& j, const std::string& where, RenderConfig c) {
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  c.validate(where);
  return c;
}

RenderConfig RenderConfig::from_json(const Json& j, const std::string& where) {
  return from_json(j, where, RenderConfig());
}

Json RenderConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::render
