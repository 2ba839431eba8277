// Options of the LiDAR odometry (plain struct with defaults, strict JSON at the edges).
// Distances in metres. Defaults follow KISS-ICP's (Vizzo et al., RA-L 2023, §III) where they
// exist; the coarse stage and the failure checks are ours (see lidar_odometry.hpp).
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::odometry {

struct OdometryConfig {
  double max_range = 80.0;   // points farther than this are dropped (protocol §1's range cut)
  double min_range = 2.0;    // and nearer than this (the vehicle itself)
  double voxel_size = -1.0;  // local-map voxel; < 0: max_range / 100 (KISS-ICP)
  int max_points_per_voxel = 20;
  // Adaptive threshold (KISS-ICP §III-C, eq. 5–6): σ before any motion sample, and the
  // smallest relative motion that counts as a sample.
  double initial_threshold = 2.0;
  double min_motion = 0.1;
  // Registration (KISS-ICP §III-D): correspondences within 3σ, Geman-McClure scale σ/3.
  int max_iterations = 500;
  double convergence = 1e-4;  // ‖Δx‖ (rad, m) below which an ICP stage has converged
  // Coarse stage (ours): before the 3σ stage, one ICP stage with correspondences within
  // max(coarse_threshold, 3σ) on a coarser source (×coarse_voxel_factor), for 2 Hz keyframes
  // metres and up to 15° apart, where the constant-velocity prediction is metres off.
  bool coarse_stage = true;
  double coarse_threshold = 6.0;
  double coarse_voxel_factor = 2.0;
  // Without a motion estimate (the second frame, or after a failed one) the coarse stage starts
  // from a grid of planar offsets of the prediction, −initial_search … +initial_search metres in
  // steps of initial_search_step along x and y (0 = off), and keeps the start whose result
  // has the most source points within inlier_distance of the fine map: a car at 2 Hz has moved
  // metres before the odometry has seen any motion, and along a straight street the ICP alone
  // does not find it.
  double initial_search = 6.0;
  double initial_search_step = 3.0;
  double inlier_distance = 0.5;
  // Coarse iterations each start of that search gets before the starts are compared (the kept
  // one then runs to convergence); 0: every start runs to convergence (slower, same choice on
  // the sequences of docs/studies/odometry).
  int initial_search_iterations = 20;
  // Failure checks: a registration with fewer source points, or whose final fraction of
  // source points with a correspondence (fitness) is lower, is reported as not converged.
  int min_points = 100;
  double min_fitness = 0.3;
  int threads = 1;  // correspondence search and normal equations; reduced in a fixed order
  // Deskewing (KISS-ICP §III-A, geometry/deskew.hpp): each scan's points are moved to the
  // frame's reference time with the sensor's per-point time model (Sensor::sweep) and the
  // constant velocity of the last two poses, before downsampling; after the registration the
  // scan is deskewed again with the velocity from the previous pose to the registered one and
  // registered once more from there (deskew_passes = 2). Off by default: the committed results
  // were made without it.
  bool deskew = false;
  int deskew_passes = 2;

  // The keys and ranges (core/config_fields.hpp); min_range's range [0, max_range] and the
  // ranges that apply only when a key is on (voxel_size > 0, initial_search > 0) are
  // validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("max_range", s.max_range, 1.0, 1e4);
    v("min_range", s.min_range);
    v("voxel_size", s.voxel_size);
    v("max_points_per_voxel", s.max_points_per_voxel, 1, 10000);
    v("initial_threshold", s.initial_threshold, 0.01, 100.0);
    v("min_motion", s.min_motion, 0.0, 100.0);
    v("max_iterations", s.max_iterations, 1, 100000);
    v("convergence", s.convergence, 1e-12, 1.0);
    v("coarse_stage", s.coarse_stage);
    v("coarse_threshold", s.coarse_threshold, 0.01, 1000.0);
    v("coarse_voxel_factor", s.coarse_voxel_factor, 1.0, 100.0);
    v("initial_search", s.initial_search, 0.0, 100.0);
    v("initial_search_step", s.initial_search_step);
    v("inlier_distance", s.inlier_distance, 0.01, 100.0);
    v("initial_search_iterations", s.initial_search_iterations, 0, 100000);
    v("min_points", s.min_points, 3, 1 << 24);
    v("min_fitness", s.min_fitness, 0.0, 1.0);
    v("threads", s.threads, 1, 256);
    v("deskew", s.deskew);
    v("deskew_passes", s.deskew_passes, 1, 10);
  }

  double resolved_voxel_size() const { return voxel_size > 0 ? voxel_size : max_range / 100.0; }
  void validate(const std::string& where) const;
  static OdometryConfig from_json(ConfigReader& r);  // reads its keys; errors name r.where()
  Json to_json() const;
};

}  // namespace sgnlf::odometry
