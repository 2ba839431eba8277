// Coarse-to-fine feature correspondences between two frames (method.md §4.2):
//   coarse: each frame's points voxel-downsampled (voxel_downsample.hpp) in the world under the
//           current poses; mutual feature nearest neighbours within a large search radius;
//   fine:   full resolution, restricted to the points of the coarse-matched voxels ("near the
//           coarse matches"); mutual feature nearest neighbours within a small radius.
// The fine matches are the pair's correspondences (E^ij, α^ij). With coarse_to_fine off the
// fine level runs over all points (the ablation).
#pragma once
#include <cstdint>
#include <vector>

#include "posegraph/feature_matching.hpp"
#include "posegraph/voxel_downsample.hpp"

namespace sgnlf::posegraph {

// One frame, ready for matching: its points in the world under the current poses with unit
// features (fine level) and their voxel representatives (coarse level, features shared).
struct FrameMatchData {
  FeatureCloud fine;
  VoxelGrid voxels;
  FeatureCloud coarse;  // coarse.x[v] = fine.x[voxels.representative[v]]
};

// Throws sgnlf::Error as FeatureCloud and voxel_downsample do.
FrameMatchData make_frame_match_data(std::vector<geometry::Point3f> x_world,
                                     std::vector<float> unit_features, int dim, double voxel_m);

struct CoarseToFineParams {
  float coarse_radius_m = 3.f;
  float fine_radius_m = 0.5f;
  bool coarse_to_fine = true;
};

struct PairMatches {
  size_t coarse = 0;                // coarse mutual matches (0 when coarse_to_fine is off)
  std::vector<FeatureMatch> fine;   // a: index into A.fine, b: into B.fine
};

PairMatches match_frames(const FrameMatchData& A, const FrameMatchData& B,
                         const CoarseToFineParams& p);

}  // namespace sgnlf::posegraph
