// The metrics entry points the pipeline and `sgnlf eval` call (protocol §4). Results are JSON
// objects with fixed key names; undefined values (NaN/∞: an empty cloud's CD, the PSNR of
// identical images, F1 without positives) and LPIPS (AlexNet weights are not shipped) are null.
#pragma once
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "geometry/range_image.hpp"
#include "geometry/se3.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::metrics {

// Keys of evaluate_view(), in order.
const std::vector<std::string>& view_metric_keys();

// One test view. `pred`: range (m), intensity, ray_drop = predicted return probability;
// `gt`: range, intensity, ray_drop = return label (0 or 1). The predicted return mask
// (probability > 0.5) multiplies predicted range and intensity, the gt label the gt range and
// intensity (as LiDAR4D's eval_step), before every metric; CD and F-score unproject the masked
// prediction and the masked GT image (range-0 pixels dropped).
// Keys: cd, fscore, depth_rmse, depth_medae, depth_ssim, depth_psnr, depth_delta1,
// depth_lpips (null), intensity_rmse, intensity_medae, intensity_ssim, intensity_psnr,
// raydrop_rmse, raydrop_acc, raydrop_f1; beside them (not in the peers' tables) cd_pred_to_gt,
// cd_gt_to_pred (CD's two terms) and depth_mse_returns, depth_mse_missed, depth_mse_false,
// raydrop_missed, raydrop_false (where depth_rmse² comes from: DepthErrorParts).
// Throws on size mismatch or non-finite inputs.
Json evaluate_view(const Sensor& sensor, const RangeImage& pred, const RangeImage& gt);

// Mean per key over views. Every view must have the same keys, each a number or null; a key
// that is null in any view is null in the mean (an undefined value is never averaged away).
Json mean_metrics(const std::vector<Json>& views);

// Which ATE a reference supports: known from the data's source (nuScenes' ego poses are planar
// by construction, z = 0, so their z carries no motion even where the LiDAR's z varies with
// roll and pitch; the twins' z is exact), or `detect`: horizontal when every ground-truth z is
// equal within kPlanarReferenceTolM (is_planar), for references of unknown origin.
enum class PoseReference { detect, full_3d, horizontal };
// ATE / RPE after Umeyama SE(3) alignment: {ate_m, ate_h_m (x, y only, same alignment),
// ate_reference ("horizontal" or "3d", per `reference`), rpe_t_cm, rpe_r_deg}.
Json pose_metrics(const std::vector<Pose>& est, const std::vector<Pose>& gt,
                  PoseReference reference = PoseReference::detect);

// What the numbers above mean, as the results record it beside them ("metric_definitions" in
// metrics.json and results.json): alignment, masks, clipping and scaling, units, thresholds.
Json definitions();

}  // namespace sgnlf::metrics
