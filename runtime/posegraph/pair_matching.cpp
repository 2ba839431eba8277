// Coarse-to-fine matching of two frames (see pair_matching.hpp).
#include "posegraph/pair_matching.hpp"

namespace sgnlf::posegraph {
namespace {

FeatureCloud coarse_cloud(const FeatureCloud& fine, const VoxelGrid& g) {
  std::vector<geometry::Point3f> x;
  std::vector<float> f;
  x.reserve(g.voxels());
  f.reserve(g.voxels() * size_t(fine.dim));
  for (uint32_t r : g.representative) {
    x.push_back(fine.x[r]);
    f.insert(f.end(), fine.row(r), fine.row(r) + fine.dim);
  }
  return FeatureCloud(std::move(x), std::move(f), fine.dim);
}

// Flags the points whose voxel is flagged.
std::vector<uint8_t> points_of_voxels(const VoxelGrid& g, const std::vector<uint8_t>& voxel_on) {
  std::vector<uint8_t> on(g.voxel_of.size(), 0);
  for (size_t k = 0; k < on.size(); ++k) on[k] = voxel_on[g.voxel_of[k]];
  return on;
}

}  // namespace

FrameMatchData make_frame_match_data(std::vector<geometry::Point3f> x_world,
                                     std::vector<float> unit_features, int dim, double voxel_m) {
  FeatureCloud fine(std::move(x_world), std::move(unit_features), dim);
  VoxelGrid g = voxel_downsample(fine.x, voxel_m);
  FeatureCloud coarse = coarse_cloud(fine, g);
  return FrameMatchData{std::move(fine), std::move(g), std::move(coarse)};
}

PairMatches match_frames(const FrameMatchData& A, const FrameMatchData& B,
                         const CoarseToFineParams& p) {
  PairMatches out;
  if (!p.coarse_to_fine) {
    out.fine = mutual_feature_matches(A.fine, B.fine, p.fine_radius_m);
    return out;
  }
  const auto coarse = mutual_feature_matches(A.coarse, B.coarse, p.coarse_radius_m);
  out.coarse = coarse.size();
  if (coarse.empty()) return out;
  std::vector<uint8_t> a_vox(A.voxels.voxels(), 0), b_vox(B.voxels.voxels(), 0);
  for (const auto& m : coarse) {
    a_vox[m.a] = 1;
    b_vox[m.b] = 1;
  }
  out.fine = mutual_feature_matches(A.fine, B.fine, p.fine_radius_m,
                                    points_of_voxels(A.voxels, a_vox),
                                    points_of_voxels(B.voxels, b_vox));
  return out;
}

}  // namespace sgnlf::posegraph
