// evaluate_view / mean_metrics / pose_metrics: protocol §4 assembled into JSON.
#include "metrics/evaluate.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "metrics/chamfer.hpp"
#include "metrics/image_metrics.hpp"
#include "metrics/masked_view.hpp"
#include "metrics/pose_errors.hpp"

namespace sgnlf::metrics {
namespace {

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

}  // namespace

const std::vector<std::string>& view_metric_keys() {
  static const std::vector<std::string> keys = {
      "cd",           "fscore",          "depth_rmse",     "depth_medae",     "depth_ssim",
      "depth_psnr",   "depth_delta1",    "depth_lpips",    "intensity_rmse",  "intensity_medae",
      "intensity_ssim", "intensity_psnr", "raydrop_rmse",  "raydrop_acc",     "raydrop_f1",
      "cd_pred_to_gt",  "cd_gt_to_pred",  "depth_mse_returns", "depth_mse_missed",
      "depth_mse_false", "raydrop_missed", "raydrop_false"};
  return keys;
}

Json evaluate_view(const Sensor& sensor, const RangeImage& pred, const RangeImage& gt) {
  const MaskedView v = mask_view(sensor, pred, gt, "evaluate_view");
  const RaydropMetrics rm = raydrop_metrics(pred.ray_drop, gt.ray_drop);  // checks labels 0/1
  const ChamferResult ch = chamfer_fscore(to_points_lidar(sensor, v.depth),
                                          to_points_lidar(sensor, v.gt_depth));
  if (ch.n_pred == 0 || ch.n_gt == 0)
    log::warn("evaluate_view: empty point cloud (", ch.n_pred, " predicted, ", ch.n_gt,
              " ground-truth points): cd = null, fscore = 0");
  const DepthMetrics dm = depth_metrics(v.depth, v.gt_depth, gt.height, gt.width);
  const DepthErrorParts parts = depth_error_parts(v.depth, v.gt_depth, pred.ray_drop, gt.ray_drop);
  const IntensityMetrics im = intensity_metrics(v.intensity, v.gt_intensity, gt.height, gt.width);

  Json j = Json::object();
  j["cd"] = number_or_null(ch.cd);
  j["fscore"] = number_or_null(ch.fscore);
  j["depth_rmse"] = number_or_null(dm.rmse);
  j["depth_medae"] = number_or_null(dm.medae);
  j["depth_ssim"] = number_or_null(dm.ssim);
  j["depth_psnr"] = number_or_null(dm.psnr);
  j["depth_delta1"] = number_or_null(dm.delta1);
  j["depth_lpips"] = nullptr;  // needs AlexNet weights, not shipped (protocol §4)
  j["intensity_rmse"] = number_or_null(im.rmse);
  j["intensity_medae"] = number_or_null(im.medae);
  j["intensity_ssim"] = number_or_null(im.ssim);
  j["intensity_psnr"] = number_or_null(im.psnr);
  j["raydrop_rmse"] = number_or_null(rm.rmse);
  j["raydrop_acc"] = number_or_null(rm.acc);
  j["raydrop_f1"] = number_or_null(rm.f1);
  // The two directions of CD (not in the peers' tables): which side the error comes from.
  j["cd_pred_to_gt"] = number_or_null(ch.cd_pred_to_gt);
  j["cd_gt_to_pred"] = number_or_null(ch.cd_gt_to_pred);
  // Where depth_rmse² comes from (not in the peers' tables either): range errors where both
  // return, and the two kinds of wrong return decision (image_metrics.hpp, DepthErrorParts).
  j["depth_mse_returns"] = number_or_null(parts.mse_returns);
  j["depth_mse_missed"] = number_or_null(parts.mse_missed);
  j["depth_mse_false"] = number_or_null(parts.mse_false);
  j["raydrop_missed"] = number_or_null(parts.missed_frac);
  j["raydrop_false"] = number_or_null(parts.false_frac);
  return j;
}

Json mean_metrics(const std::vector<Json>& views) {
  require(!views.empty(), "mean_metrics: no views to average");
  for (size_t v = 0; v < views.size(); ++v)
    require(views[v].is_object(), "mean_metrics: view " + std::to_string(v) + " is not an object");
  Json out = Json::object();
  for (const auto& [key, first] : views[0].items()) {
    double sum = 0.0;
    bool any_null = false;
    for (size_t v = 0; v < views.size(); ++v) {
      require(views[v].contains(key),
              "mean_metrics: view " + std::to_string(v) + " lacks key '" + key + "'");
      const Json& x = views[v][key];
      require(x.is_null() || x.is_number(), "mean_metrics: view " + std::to_string(v) +
                                                " key '" + key + "' is " + x.dump());
      if (x.is_null())
        any_null = true;
      else
        sum += x.get<double>();
    }
    out[key] = any_null ? Json(nullptr) : number_or_null(sum / double(views.size()));
  }
  for (size_t v = 1; v < views.size(); ++v)
    require(views[v].size() == views[0].size(),
            "mean_metrics: view " + std::to_string(v) + " has " +
                std::to_string(views[v].size()) + " keys, view 0 has " +
                std::to_string(views[0].size()));
  return out;
}

Json pose_metrics(const std::vector<Pose>& est, const std::vector<Pose>& gt,
                  PoseReference reference) {
  const PoseErrors e = compute_pose_errors(est, gt);
  const bool horizontal = reference == PoseReference::detect ? e.planar_reference
                                                             : reference == PoseReference::horizontal;
  return Json{{"ate_m", number_or_null(e.ate_m)},
              {"ate_h_m", number_or_null(e.ate_h_m)},
              {"ate_reference", horizontal ? "horizontal" : "3d"},
              {"rpe_t_cm", number_or_null(e.rpe_t_cm)},
              {"rpe_r_deg", number_or_null(e.rpe_r_deg)}};
}

Json definitions() {
  return Json{
      {"version", 1},
      {"pose", {{"alignment", "Umeyama SE(3) on the positions, scale fixed to 1, applied to every estimated pose"},
                {"ate_m", "sqrt(mean |p_gt - p_aligned|^2), metres, 3D"},
                {"ate_h_m", "sqrt(mean |(p_gt - p_aligned)_xy|^2), metres: ate_m over x and y only, under the same 3D alignment"},
                {"ate_reference", "which ATE the reference poses support: horizontal when the dataset's reference poses are planar (nuScenes' ego poses, z = 0, also in a window sgnlf bench copied from nuScenes; where no dataset says, when every ground-truth z is equal within 1e-6 m), else 3d"},
                {"rpe", "consecutive pairs of aligned poses; rpe_t_cm mean translation error in cm, rpe_r_deg mean rotation angle in degrees"}}},
      {"raydrop_mask", "predicted: return probability > 0.5 multiplies the predicted range and intensity; the ground-truth return label multiplies the ground truth (LiDAR4D's eval_step)"},
      {"depth", {{"units", "metres"}, {"clip_m", {1e-6, 80.0}},
                 {"psnr", "10 log10(80^2 / MSE)"},
                 {"ssim_data_range", "max(gt) - min(gt) after clipping"},
                 {"delta1", "fraction with max(gt/pred, pred/gt) < 1.25"},
                 {"medae", "median |gt - pred|"},
                 {"mse_parts", "depth_mse_returns + depth_mse_missed + depth_mse_false = depth_rmse^2 of each frame: the squared errors where both return, where the ground truth returns and the prediction drops, and where the prediction returns and the ground truth drops, each summed over its pixels and divided by all pixels; raydrop_missed and raydrop_false are those pixels' fractions"}}},
      {"intensity", {{"scale", "reflectance in [0, 1]: KITTI remission as stored, nuScenes intensity / 255, the twins' simulated reflectance"},
                     {"clip", {1e-6, 1.0}}, {"psnr", "10 log10(1 / MSE)"}}},
      {"raydrop", "rmse of the return probability against the label; acc and f1 of probability > 0.5"},
      {"depth_variants", "model views rendered by the protocol renderer also record median_<m> (the median depth on every ray) and mix_<m> (the median depth where a ray's weight-normalised depth variance exceeds 10x the frame's median variance, GS-LiDAR's; mix_median_fraction: the share of such rays) for m in cd, cd_gt_to_pred, cd_pred_to_gt, fscore, depth_rmse, depth_medae, and opacity_mean (mean sum of weights over the rays predicted to return); the tables report the expected depth"},
      {"point_cloud", {{"cd", "mean nearest squared distance both ways, summed, m^2, of the masked prediction and the masked ground truth unprojected"},
                       {"fscore_threshold_sq_m2", kFscoreThresholdSq}}},
      {"per_frame", "every mean is over the per-frame values recorded beside it; an undefined value (null) in any frame makes the mean null"}};
}

}  // namespace sgnlf::metrics
