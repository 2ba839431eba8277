// LidarOdometry (see lidar_odometry.hpp).
#include "odometry/lidar_odometry.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "geometry/deskew.hpp"
#include "odometry/motion_model.hpp"
#include "odometry/voxel_grid.hpp"

namespace sgnlf::odometry {

LidarOdometry::LidarOdometry(const OdometryConfig& config, const SweepTiming& sweep, double sweep_duration_s)
    : cfg_((config.validate("odometry"), config)),
      sweep_(sweep),
      sweep_duration_s_(sweep_duration_s),
      map_(config.resolved_voxel_size(), config.max_points_per_voxel, config.max_range),
      coarse_map_(0.5 * config.coarse_threshold, config.max_points_per_voxel, config.max_range),
      threshold_(config.initial_threshold, config.min_motion, config.max_range) {
  sweep_.validate("odometry: sweep");
  if (cfg_.deskew && !(sweep_duration_s_ > 0))
    throw ConfigError("odometry: 'deskew' needs the sensor's sweep duration (got " +
                      std::to_string(sweep_duration_s_) + " s)");
}

Cloud LidarOdometry::deskewed(const Cloud& scan_lidar, const Pose& T_world_a, const Pose& T_world_b,
                              double dt_s) const {
  return deskew(scan_lidar, sweep_, sweep_duration_s_, constant_velocity_twist(T_world_a, T_world_b, dt_s));
}

Cloud LidarOdometry::transformed(const Cloud& c, const Pose& T) {
  Cloud out(c.size());
  for (size_t i = 0; i < c.size(); ++i) out[i] = T * c[i];
  return out;
}

FrameResult LidarOdometry::register_frame(const Cloud& scan_lidar, double timestamp_s) {
  if (!timestamps_.empty() && timestamp_s < timestamps_.back())
    throw Error("LidarOdometry: timestamp " + std::to_string(timestamp_s) +
                " s is before the previous frame's " + std::to_string(timestamps_.back()) + " s");
  const double v = cfg_.resolved_voxel_size();
  const size_t n = poses_.size();
  // Step 0 (KISS-ICP §III-A, with cfg_.deskew): deskew with the last two poses' velocity.
  Cloud scan;
  const Cloud* in = &scan_lidar;
  if (cfg_.deskew && n >= 2 && timestamps_[n - 1] > timestamps_[n - 2]) {
    scan = deskewed(scan_lidar, poses_[n - 2], poses_[n - 1], timestamps_[n - 1] - timestamps_[n - 2]);
    in = &scan;
  }
  // Step 1 (KISS-ICP §III-B): the map keeps the 0.5 v grid, ICP registers the 1.5 v grid.
  Cloud frame = voxel_downsample(crop_range(*in, cfg_.min_range, cfg_.max_range), 0.5 * v);
  Cloud source = voxel_downsample(frame, 1.5 * v);
  FrameResult fr;
  fr.source_points = source.size();
  fr.sigma = threshold_.sigma();
  // Step 2: constant-velocity prediction.
  fr.T_world_lidar_predicted = predict_constant_velocity(poses_, timestamps_, timestamp_s);
  fr.T_world_lidar = fr.T_world_lidar_predicted;
  if (map_.empty()) {
    fr.initialised_map = true;
  } else {
    RegistrationOptions o;
    o.max_iterations = cfg_.max_iterations;
    o.convergence = cfg_.convergence;
    o.min_points = cfg_.min_points;
    o.min_fitness = cfg_.min_fitness;
    o.threads = cfg_.threads;
    Pose guess = fr.T_world_lidar_predicted;
    int coarse_iterations = 0;
    // Step 3a (ours): the coarse stage pulls a prediction metres off into the fine basin.
    if (cfg_.coarse_stage) {
      const Cloud coarse_source = voxel_downsample(source, cfg_.coarse_voxel_factor * 1.5 * v);
      RegistrationOptions oc = o;
      oc.max_distance = std::max(cfg_.coarse_threshold, 3.0 * fr.sigma);
      oc.kernel_scale = oc.max_distance / 3.0;
      oc.min_points = std::max(3, std::min(o.min_points, int(coarse_source.size())));
      oc.min_fitness = 0.0;
      // Starts: the prediction, and without a motion estimate the grid of planar offsets.
      std::vector<Pose> starts{guess};
      const double step = cfg_.initial_search_step, reach = cfg_.initial_search;
      if (!has_motion_ && reach > 0) {
        const int n = int(std::floor(reach / step + 1e-9));
        for (int ix = -n; ix <= n; ++ix)
          for (int iy = -n; iy <= n; ++iy) {
            if (ix == 0 && iy == 0) continue;
            Pose s = guess;
            s.translation() += guess.linear() * Vec3(ix * step, iy * step, 0.0);
            starts.push_back(s);
          }
      }
      // With several starts each is probed with at most initial_search_iterations coarse
      // iterations (0: to convergence), and only the kept one is then run to convergence.
      const bool probe = starts.size() > 1 && cfg_.initial_search_iterations > 0;
      RegistrationOptions op = oc;
      if (probe) op.max_iterations = std::min(oc.max_iterations, cfg_.initial_search_iterations);
      // A coarse result is usable when it converged or only ran out of iterations.
      const auto usable = [](const RegistrationResult& rc) {
        return rc.failure.empty() || rc.failure.rfind("no convergence", 0) == 0;
      };
      double best_overlap = -1.0;
      for (const Pose& start : starts) {
        const RegistrationResult rc = register_scan(coarse_source, coarse_map_, start, op);
        coarse_iterations += rc.iterations;
        if (!usable(rc)) continue;
        const double overlap = starts.size() == 1 ? 1.0
            : overlap_fraction(source, map_, rc.T_world_source, cfg_.inlier_distance);
        if (overlap > best_overlap) {  // strict: ties keep the earlier start (the prediction)
          best_overlap = overlap;
          guess = rc.T_world_source;
        }
      }
      if (probe) {
        const RegistrationResult rc = register_scan(coarse_source, coarse_map_, guess, oc);
        coarse_iterations += rc.iterations;
        if (usable(rc)) guess = rc.T_world_source;
      }
    }
    // Step 3b (KISS-ICP §III-D): 3σ correspondences, Geman-McClure κ = σ/3.
    o.max_distance = 3.0 * fr.sigma;
    o.kernel_scale = fr.sigma / 3.0;
    fr.registration = register_scan(source, map_, guess, o);
    fr.registration.iterations += coarse_iterations;
    if (!fr.registration.converged) {
      has_motion_ = false;  // the next frame searches around its prediction again
      fr.map_points = map_.num_points();
      poses_.push_back(fr.T_world_lidar);
      timestamps_.push_back(timestamp_s);
      return fr;
    }
    fr.T_world_lidar = fr.registration.T_world_source;
    // Deskew passes after the first: the velocity from the previous pose to this frame's
    // registered one, then the fine stage again from the registered pose.
    for (int pass = 1; cfg_.deskew && pass < cfg_.deskew_passes && timestamp_s > timestamps_.back(); ++pass) {
      scan = deskewed(scan_lidar, poses_.back(), fr.T_world_lidar, timestamp_s - timestamps_.back());
      frame = voxel_downsample(crop_range(scan, cfg_.min_range, cfg_.max_range), 0.5 * v);
      source = voxel_downsample(frame, 1.5 * v);
      RegistrationResult again = register_scan(source, map_, fr.T_world_lidar, o);
      if (!again.converged) break;
      again.iterations += fr.registration.iterations;
      fr.registration = again;
      fr.T_world_lidar = again.T_world_source;
      fr.source_points = source.size();
    }
    has_motion_ = true;
    // Step 4: σ from the model deviation (eq. 5–6).
    threshold_.update(fr.T_world_lidar_predicted.inverse() * fr.T_world_lidar);
  }
  const Cloud frame_world = transformed(frame, fr.T_world_lidar);
  map_.update(frame_world, fr.T_world_lidar.translation());
  coarse_map_.update(frame_world, fr.T_world_lidar.translation());
  fr.map_points = map_.num_points();
  poses_.push_back(fr.T_world_lidar);
  timestamps_.push_back(timestamp_s);
  return fr;
}

}  // namespace sgnlf::odometry
