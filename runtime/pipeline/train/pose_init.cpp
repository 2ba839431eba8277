// initial_poses (see pose_init.hpp).
#include "pipeline/train/pose_init.hpp"

#include "core/error.hpp"
#include "datasets/protocol.hpp"
#include "odometry/trajectory.hpp"

namespace sgnlf::pipeline {
namespace {

// The built-in LiDAR odometry on the frames' own scans (default options; first frame at the
// identity). A frame that does not register is an error, not a silently wrong start.
std::vector<Pose> odometry_poses(const Dataset& d) {
  std::vector<const std::vector<PointXYZI>*> scans;
  std::vector<double> stamps;
  for (const auto& f : d.frames) {
    scans.push_back(&f.points);
    stamps.push_back(f.timestamp_s);
  }
  const auto r = odometry::estimate_trajectory(scans, stamps, odometry::OdometryConfig{}, d.sensor);
  if (!r.failed.empty()) {
    const int k = r.failed.front();
    throw Error("poses.init = \"odometry\": " + std::to_string(r.failed.size()) + " of " +
                std::to_string(d.frames.size()) + " frames of " + d.name +
                " did not register, the first frame id " + std::to_string(d.frames[size_t(k)].id) +
                ": " + r.frames[size_t(k)].registration.failure + " (sgnlf odometry --log shows all)");
  }
  return r.T_world_lidar;
}

}  // namespace

std::vector<Pose> initial_poses(const Dataset& d, const PoseInitConfig& c) {
  if (!d.has_reference_poses && (c.init == "gt" || c.init == "noisy"))
    throw ConfigError("poses.init = \"" + c.init + "\": " + d.path +
                      " holds scans without reference poses, so there is nothing to start from "
                      "or perturb; use \"odometry\" (--pose-init odometry, what sgnlf "
                      "reconstruct does) or \"identity\"");
  const std::vector<Pose> gt = gt_poses(d);
  if (c.init == "gt") return gt;
  if (c.init == "noisy") return perturb_poses(gt, c.noise_seed, c.sigma_rot_rad, c.sigma_trans_m);
  if (c.init == "identity") return identity_poses(gt.size());
  if (c.init == "odometry") return odometry_poses(d);
  throw ConfigError("poses.init = \"" + c.init +
                    "\" is not one of \"gt\", \"noisy\", \"identity\", \"odometry\"");
}

}  // namespace sgnlf::pipeline
