// Scan-to-map registration (KISS-ICP §III-D): point-to-point ICP, Gauss-Newton on a left
// perturbation T ← Exp(δ)·T, δ = (ω, u), with the Geman-McClure weight
// w(r²) = κ² / (κ + r²)² (KISS-ICP eq. 7, κ = σ/3) and correspondences from the voxel map
// within `max_distance` (3σ). Returns a result instead of printing, small_gicp style.
#pragma once
#include <string>

#include "geometry/se3.hpp"
#include "odometry/voxel_map.hpp"

namespace sgnlf::odometry {

struct RegistrationOptions {
  double max_distance = 6.0;   // correspondences farther than this are ignored (metres)
  double kernel_scale = 0.67;  // κ of the Geman-McClure weight
  int max_iterations = 500;
  double convergence = 1e-4;   // stop when ‖δ‖ < this
  int min_points = 100;        // fewer source points: a failure
  double min_fitness = 0.3;    // lower final inlier fraction: a failure
  int threads = 1;             // fixed contiguous chunks, summed in chunk order
};

struct RegistrationResult {
  Pose T_world_source = Pose::Identity();  // the estimate (the initial guess on early failure)
  bool converged = false;  // ‖δ‖ fell below the criterion and the checks passed
  int iterations = 0;
  double fitness = 0.0;    // fraction of source points with a correspondence at the end
  double rmse = 0.0;       // RMS distance of those correspondences (metres)
  size_t correspondences = 0;
  size_t source_points = 0;
  std::string failure;     // empty when converged, else why not
};

// Fraction of `source` points (under T_world_source) whose nearest map point lies within
// `max_distance`: the fitness of a pose.
double overlap_fraction(const Cloud& source, const VoxelHashMap& map, const Pose& T_world_source,
                        double max_distance);

// Registers `source` (sensor frame) to `map` (world frame) starting at `T_world_source_guess`.
RegistrationResult register_scan(const Cloud& source, const VoxelHashMap& map,
                                 const Pose& T_world_source_guess, const RegistrationOptions& opt);

}  // namespace sgnlf::odometry
