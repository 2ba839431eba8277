// PoseFreeConfig: strict JSON reading, writing and validation (see pose_free_config.hpp).
#include "pipeline/config/pose_free_config.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf::pipeline {

int GeometricScheduleConfig::steps_at(long epoch, double progress) const {
  if (!enabled) return 0;
  if (epoch == 0) return first_steps;
  if (progress >= stop_progress) return 0;
  return int(std::lround(steps_per_epoch * (1.0 - progress / stop_progress)));
}

void PoseFreeConfig::validate(const std::string& w) const {
  if (poses.init != "gt" && poses.init != "noisy" && poses.init != "identity" &&
      poses.init != "odometry")
    throw ConfigError(w + ".poses: 'init' = \"" + poses.init +
                      "\" is not one of \"gt\", \"noisy\", \"identity\", \"odometry\"");
  config::check_fields(*this, w);
  const std::string g = w + ".geometric";
  if (geometric.tau_scale != -1.0) check_range(g, "tau_scale", geometric.tau_scale, 0.0, 100.0);
  if (geometric.edge_offsets.empty()) throw ConfigError(g + ": 'edge_offsets' is empty");
  if (geometric.residual != "point_to_point" && geometric.residual != "point_to_plane")
    throw ConfigError(g + ": 'residual' = \"" + geometric.residual +
                      "\" is not one of \"point_to_point\", \"point_to_plane\"");
  for (int k : geometric.edge_offsets) check_range(g, "edge_offsets[]", k, 1, 1000);
}

PoseFreeConfig PoseFreeConfig::from_json(ConfigReader& r) {
  PoseFreeConfig c;
  config::read_fields_here(r, c);
  return c;
}

void PoseFreeConfig::to_json(Json& j) const { j.update(config::write_fields(*this)); }

}  // namespace sgnlf::pipeline
