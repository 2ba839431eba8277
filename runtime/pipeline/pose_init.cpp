// initial_poses (see pose_init.hpp).
#include "pipeline/pose_init.hpp"

#include "core/error.hpp"
#include "datasets/protocol.hpp"

namespace sgnlf::pipeline {

std::vector<Pose> initial_poses(const Dataset& d, const PoseInitConfig& c) {
  const std::vector<Pose> gt = gt_poses(d);
  if (c.init == "gt") return gt;
  if (c.init == "noisy") return perturb_poses(gt, c.noise_seed, c.sigma_rot_rad, c.sigma_trans_m);
  if (c.init == "identity") return identity_poses(gt.size());
  throw ConfigError("poses.init = \"" + c.init + "\" is not one of \"gt\", \"noisy\", \"identity\"");
}

}  // namespace sgnlf::pipeline
