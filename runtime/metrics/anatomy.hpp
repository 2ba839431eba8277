// The error anatomy of one test view (issue 66): where its Chamfer distance (both directions)
// and its depth MSE come from, split by cause and by bin so that the parts add up exactly to
// evaluate_view's cd_pred_to_gt, cd_gt_to_pred and depth_rmse² (docs/anatomy.md).
//   cause: both (the pixel returns in the prediction and the ground truth: a range error),
//          missed (the ground truth returns, the prediction drops), false (the prediction
//          returns where the ground truth dropped). pred → GT has both and false; GT → pred
//          both and missed; the depth MSE all three (image_metrics.hpp DepthErrorParts).
//   range band: by the ground truth's range where it returns, else the prediction's (a false
//          return's), kAnatomyRangeEdgesM.
//   row: the pixel's beam row.
//   train distance: from the pixel's point (the ground truth's, else the prediction's) to the
//          nearest point of any training scan, in the world frame, kAnatomyTrainEdgesM; only
//          with TrainingPoints.
// Each CD part is the sum of its points' squared NN distances divided by that direction's point
// count; each depth part the sum of its pixels' squared clipped errors divided by all pixels.
// Inputs and masking are evaluate_view's (masked_view.hpp).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "geometry/kdtree.hpp"
#include "geometry/range_image.hpp"
#include "geometry/se3.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::metrics {

inline constexpr std::array<double, 4> kAnatomyRangeEdgesM = {10.0, 20.0, 40.0, 80.0};
inline constexpr std::array<double, 3> kAnatomyTrainEdgesM = {0.1, 0.5, 2.0};
constexpr int kAnatomyCauses = 3, kAnatomyRangeBands = 5, kAnatomyTrainBands = 4;
enum AnatomyCause : int { kCauseBoth = 0, kCauseMissed = 1, kCauseFalse = 2 };

// Names as the JSON keys write them: "both", "missed", "false"; "0-10m", ..., "80m+";
// "<0.1m", "0.1-0.5m", "0.5-2m", "2m+".
const std::array<std::string, kAnatomyCauses>& anatomy_cause_names();
const std::array<std::string, kAnatomyRangeBands>& anatomy_range_band_names();
const std::array<std::string, kAnatomyTrainBands>& anatomy_train_band_names();
int anatomy_range_band(double range_m);  // edges belong to the upper band
int anatomy_train_band(double distance_m);

// The training scans' points in the world frame and the test view's pose.
struct TrainingPoints {
  const geometry::KdTree* points_world = nullptr;
  Pose T_world_lidar = Pose::Identity();  // the test view's LiDAR frame → world
};

// One quantity split. Every split sums to `total` (to rounding); all NaN when the quantity is
// undefined (a CD direction with an empty cloud).
struct ErrorSplit {
  double total = 0.0;
  std::array<std::array<double, kAnatomyRangeBands>, kAnatomyCauses> by_cause_range{};
  std::vector<double> by_row;                      // sensor height entries
  std::array<double, kAnatomyTrainBands> by_train{};  // NaN without TrainingPoints
  double cause(int c) const;
  double band(int b) const;
};

struct ViewAnatomy {
  ErrorSplit cd_pred_to_gt, cd_gt_to_pred, depth_mse;
  // Share of all pixels per depth cause and range band (neither returning: not counted).
  std::array<std::array<double, kAnatomyRangeBands>, kAnatomyCauses> pixels{};
  size_t n_pred = 0, n_gt = 0;  // the point clouds CD compares
  bool has_train = false;
  // Per pixel: image_metrics.hpp ReturnCase as an integer (for the picture).
  std::vector<uint8_t> pixel_case;
};

// Throws sgnlf::Error as evaluate_view does (sizes, non-finite values, labels not 0/1), and for
// TrainingPoints with an empty or null tree or a non-finite pose.
ViewAnatomy view_anatomy(const Sensor& sensor, const RangeImage& pred, const RangeImage& gt,
                         const TrainingPoints* train = nullptr);

}  // namespace sgnlf::metrics
