// OdometryConfig: validation and strict JSON (see odometry_config.hpp).
#include "odometry/odometry_config.hpp"

namespace sgnlf::odometry {

void OdometryConfig::validate(const std::string& w) const {
  check_range(w, "max_range", max_range, 1.0, 1e4);
  check_range(w, "min_range", min_range, 0.0, max_range);
  if (voxel_size > 0) check_range(w, "voxel_size", voxel_size, 0.01, 100.0);
  check_range(w, "max_points_per_voxel", max_points_per_voxel, 1, 10000);
  check_range(w, "initial_threshold", initial_threshold, 0.01, 100.0);
  check_range(w, "min_motion", min_motion, 0.0, 100.0);
  check_range(w, "max_iterations", max_iterations, 1, 100000);
  check_range(w, "convergence", convergence, 1e-12, 1.0);
  check_range(w, "coarse_threshold", coarse_threshold, 0.01, 1000.0);
  check_range(w, "coarse_voxel_factor", coarse_voxel_factor, 1.0, 100.0);
  check_range(w, "initial_search", initial_search, 0.0, 100.0);
  if (initial_search > 0) check_range(w, "initial_search_step", initial_search_step, 0.1, 100.0);
  check_range(w, "inlier_distance", inlier_distance, 0.01, 100.0);
  check_range(w, "initial_search_iterations", initial_search_iterations, 0, 100000);
  check_range(w, "min_points", min_points, 3, 1 << 24);
  check_range(w, "min_fitness", min_fitness, 0.0, 1.0);
  check_range(w, "threads", threads, 1, 256);
  check_range(w, "deskew_passes", deskew_passes, 1, 10);
}

OdometryConfig OdometryConfig::from_json(ConfigReader& r) {
  OdometryConfig c;
  r.get("max_range", c.max_range).get("min_range", c.min_range).get("voxel_size", c.voxel_size);
  r.get("max_points_per_voxel", c.max_points_per_voxel);
  r.get("initial_threshold", c.initial_threshold).get("min_motion", c.min_motion);
  r.get("max_iterations", c.max_iterations).get("convergence", c.convergence);
  r.get("coarse_stage", c.coarse_stage).get("coarse_threshold", c.coarse_threshold);
  r.get("coarse_voxel_factor", c.coarse_voxel_factor).get("initial_search", c.initial_search);
  r.get("initial_search_step", c.initial_search_step).get("inlier_distance", c.inlier_distance);
  r.get("initial_search_iterations", c.initial_search_iterations);
  r.get("min_points", c.min_points).get("min_fitness", c.min_fitness).get("threads", c.threads);
  r.get("deskew", c.deskew).get("deskew_passes", c.deskew_passes);
  r.finish();
  c.validate(r.where());
  return c;
}

Json OdometryConfig::to_json() const {
  return Json{{"max_range", max_range},
              {"min_range", min_range},
              {"voxel_size", voxel_size},
              {"max_points_per_voxel", max_points_per_voxel},
              {"initial_threshold", initial_threshold},
              {"min_motion", min_motion},
              {"max_iterations", max_iterations},
              {"convergence", convergence},
              {"coarse_stage", coarse_stage},
              {"coarse_threshold", coarse_threshold},
              {"coarse_voxel_factor", coarse_voxel_factor},
              {"initial_search", initial_search},
              {"initial_search_step", initial_search_step},
              {"inlier_distance", inlier_distance},
              {"initial_search_iterations", initial_search_iterations},
              {"min_points", min_points},
              {"min_fitness", min_fitness},
              {"threads", threads},
              {"deskew", deskew},
              {"deskew_passes", deskew_passes}};
}

}  // namespace sgnlf::odometry
