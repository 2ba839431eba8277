// PoseFreeConfig: strict JSON reading, writing and validation (see pose_free_config.hpp).
#include "pipeline/config/pose_free_config.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf::pipeline {

int GeometricScheduleConfig::steps_at(long epoch, double progress) const {
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
  if (geometric) {
    if (!pose_optim.optimize)
      throw ConfigError(w + ".geometric: the geometric stage moves the poses, and "
                        "pose_optim.optimize is false; remove the section (\"geometric\": null)");
    geometric->optimizer.validate(w + ".geometric.optimizer");
    if (geometric->reseed) geometric->reseed->validate(w + ".geometric.reseed");
    if (geometric->refine) geometric->refine->optimizer.validate(w + ".geometric.refine.optimizer");
  }
}

posegraph::GeometricConfig GeometricScheduleConfig::default_optimizer() {
  posegraph::GeometricConfig g;
  g.lr_rotation = 1e-2;
  g.lr_translation = 1e-1;
  g.points_per_frame = 12000;
  g.threads = 2;
  return g;
}

posegraph::GeometricConfig GeometricRefineConfig::default_optimizer() {
  posegraph::GeometricConfig g;
  g.edge_offsets = {1, 2, 3, 4, 5, 6, 7, 8};
  g.lr_rotation = 5e-4;
  g.lr_translation = 5e-3;
  g.tau_scale = 4.0;
  g.points_per_frame = 16000;
  g.threads = 2;
  g.residual = "point_to_plane";
  return g;
}

PoseFreeConfig PoseFreeConfig::from_json(ConfigReader& r) {
  PoseFreeConfig c;
  config::read_fields_here(r, c);
  return c;
}

void PoseFreeConfig::to_json(Json& j) const { j.update(config::write_fields(*this)); }

}  // namespace sgnlf::pipeline
