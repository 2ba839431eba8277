// The evaluation protocol's dataset-side pieces: train/test splits (protocol §3), scene
// normalisation (protocol §2) and the pose-free initialisations (protocol §3, GeoNLF).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "datasets/dataset.hpp"

namespace sgnlf {

// standard: every 13th frame from 13 is a test frame (13, 26, 39, 52 of 64);
// low: frames 4, 12, 20 are test frames (those < n_frames). All others train.
Split protocol_split(int n_frames, const std::string& frequency);
// LiDAR4D's dynamic KITTI-360 set (its released preprocessing): windows of 51 frames at 10 Hz
// whose frames 10, 20, 30 and 40 are the test frames, kept out of training. In general every
// 10th frame strictly inside the window (0 < k < n − 1): a shorter window keeps its first
// and last frames for training.
Split dynamic_split(int n_frames);
// The split named by a sequence: "protocol" (protocol_split) or "dynamic" (dynamic_split).
Split named_split(const std::string& split, int n_frames, const std::string& frequency);

// Union of the given frames' points (range inside the sensor's (min, max)) in world
// coordinates under `T_world_lidar`; center = bbox midpoint, scale = 1 / max |centred coord|.
SceneNormalization compute_normalization(const Dataset& d, const std::vector<Pose>& T_world_lidar,
                                         const std::vector<int>& frames);

// T_gt · Exp(ξ), ξ = (ω, u), ω ~ N(0, σ_rot²), u ~ N(0, σ_trans²) per axis, right-multiplied with
// the decoupled exponential; draws from Rng(seed) in frame order (ω xyz, then u xyz).
std::vector<Pose> perturb_poses(const std::vector<Pose>& T_gt, uint64_t seed,
                                double sigma_rot_rad = 0.151, double sigma_trans_m = 2.0);
// The second pose-free protocol: every pose starts at the identity.
std::vector<Pose> identity_poses(size_t n);

std::vector<Pose> gt_poses(const Dataset& d);

}  // namespace sgnlf
