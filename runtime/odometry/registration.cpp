// register_scan (see registration.hpp).
#include "odometry/registration.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <thread>
#include <vector>

#include "core/error.hpp"
#include "odometry/normal_equations.hpp"

namespace sgnlf::odometry {
namespace {

void accumulate(const Cloud& source, size_t begin, size_t end, const VoxelHashMap& map,
                const Pose& T, double max_d2, double kernel, bool build, NormalEquations& n) {
  const double k2 = kernel * kernel;
  for (size_t i = begin; i < end; ++i) {
    const Point3 p = T * source[i];
    Point3 q;
    double d2;
    if (!map.nearest(p, q, d2) || d2 > max_d2) continue;
    n.count_point(d2);
    if (!build) continue;
    const double s = kernel + d2;
    n.add_point(p, p - q, k2 / (s * s));  // Geman-McClure weight
  }
}

NormalEquations build_system(const Cloud& source, const VoxelHashMap& map, const Pose& T,
                             double max_d2, double kernel, bool build, int threads) {
  const size_t n = source.size();
  const int t = std::max(1, std::min<int>(threads, int(n / 256) + 1));
  std::vector<NormalEquations> parts(static_cast<size_t>(t));
  if (t == 1) {
    accumulate(source, 0, n, map, T, max_d2, kernel, build, parts[0]);
  } else {
    std::vector<std::thread> pool;
    for (int k = 0; k < t; ++k)
      pool.emplace_back([&, k] {
        accumulate(source, n * size_t(k) / size_t(t), n * size_t(k + 1) / size_t(t), map, T,
                   max_d2, kernel, build, parts[size_t(k)]);
      });
    for (auto& th : pool) th.join();
  }
  NormalEquations sum = parts[0];
  for (size_t k = 1; k < parts.size(); ++k) sum.add(parts[k]);
  return sum;
}

}  // namespace

double overlap_fraction(const Cloud& source, const VoxelHashMap& map, const Pose& T_world_source,
                        double max_distance) {
  if (source.empty()) return 0.0;
  const NormalEquations n = build_system(source, map, T_world_source, max_distance * max_distance, 1.0,
                                false, 1);
  return double(n.count) / double(source.size());
}

RegistrationResult register_scan(const Cloud& source, const VoxelHashMap& map,
                                 const Pose& T_world_source_guess, const RegistrationOptions& opt) {
  if (!(opt.max_distance > 0) || !(opt.kernel_scale > 0) || opt.max_iterations < 1 ||
      opt.min_points < 3 || opt.threads < 1)
    throw ConfigError("register_scan: max_distance and kernel_scale must be > 0, "
                      "max_iterations >= 1, min_points >= 3, threads >= 1");
  RegistrationResult res;
  res.T_world_source = T_world_source_guess;
  res.source_points = source.size();
  if (int(source.size()) < opt.min_points) {
    res.failure = "too few points: " + std::to_string(source.size()) + " < " +
                  std::to_string(opt.min_points);
    return res;
  }
  if (map.empty()) {
    res.failure = "the map is empty";
    return res;
  }
  const double max_d2 = opt.max_distance * opt.max_distance;
  Pose T = T_world_source_guess;
  bool step_converged = false;
  for (int it = 0; it < opt.max_iterations; ++it) {
    const NormalEquations n = build_system(source, map, T, max_d2, opt.kernel_scale, true, opt.threads);
    res.iterations = it + 1;
    if (n.count < 6) {
      res.T_world_source = T;
      res.correspondences = n.count;
      res.failure = "no overlap: " + std::to_string(n.count) + " correspondences within " +
                    std::to_string(opt.max_distance) + " m at iteration " + std::to_string(it + 1);
      return res;
    }
    const Vec6 dx = -n.JTJ().ldlt().solve(n.JTr);
    if (!dx.allFinite()) {
      res.T_world_source = T;
      res.failure = "degenerate normal equations";
      return res;
    }
    T = exp_se3(dx) * T;
    if (dx.norm() < opt.convergence) {
      step_converged = true;
      break;
    }
  }
  res.T_world_source = T;
  const NormalEquations fin = build_system(source, map, T, max_d2, opt.kernel_scale, false, opt.threads);
  res.correspondences = fin.count;
  res.fitness = double(fin.count) / double(source.size());
  res.rmse = fin.count ? std::sqrt(fin.sse / double(fin.count)) : 0.0;
  if (!step_converged) {
    res.failure = "no convergence in " + std::to_string(opt.max_iterations) + " iterations";
  } else if (res.fitness < opt.min_fitness) {
    res.failure = "low overlap: fitness " + std::to_string(res.fitness) + " < " +
                  std::to_string(opt.min_fitness);
  } else {
    res.converged = true;
  }
  return res;
}

}  // namespace sgnlf::odometry
