// OdometryConfig: validation and strict JSON (see odometry_config.hpp).
#include "core/config_fields.hpp"
#include "odometry/odometry_config.hpp"

#include "core/config.hpp"

namespace sgnlf::odometry {

void OdometryConfig::validate(const std::string& w) const {
  config::check_fields(*this, w);
  check_range(w, "min_range", min_range, 0.0, max_range);
  if (voxel_size > 0) check_range(w, "voxel_size", voxel_size, 0.01, 100.0);
  if (initial_search > 0) check_range(w, "initial_search_step", initial_search_step, 0.1, 100.0);
}

OdometryConfig OdometryConfig::from_json(ConfigReader& r) {
  OdometryConfig c;
  config::read_fields_here(r, c);
  r.finish();
  c.validate(r.where());
  return c;
}

Json OdometryConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::odometry
