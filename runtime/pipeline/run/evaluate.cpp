// evaluate_model / evaluate_naive (see evaluate.hpp).
#include "pipeline/run/evaluate.hpp"

#include <algorithm>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/protocol.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/naive_baseline.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/model/view_rules.hpp"
#include "pipeline/run/ray_drop_stage.hpp"

namespace sgnlf::pipeline {
namespace {

// The depth metrics recorded beside the protocol's for the median and "mix" depths.
constexpr const char* kAltDepthKeys[] = {"cd", "cd_gt_to_pred", "cd_pred_to_gt", "fscore",
                                         "depth_rmse", "depth_medae"};

// Beside the protocol's expected depth (the tables' metric): the same prediction with the
// median depth on every ray ("median_*"), and with the median depth where a ray's depth
// variance exceeds 10× the frame's median variance ("mix_*", as GS-LiDAR reports it); the mix's
// share of median rays, and the mean opacity Σ w of the rays predicted to return.
void add_depth_variants(Json& m, const Dataset& d, int f, const RangeImage& pred,
                        const DepthStats& st) {
  const RangeImage& gt = d.frames[size_t(f)].image;
  RangeImage med = pred, mix = pred;
  const size_t mixed = apply_mix_depth(mix, st);
  size_t returning = 0;
  double opacity = 0.0;
  for (size_t p = 0; p < pred.size(); ++p) {
    med.range[p] = st.median_m[p];
    if (pred.ray_drop[p] > 0.5f) opacity += st.opacity[p], ++returning;
  }
  const Json jm = metrics::evaluate_view(d.sensor, med, gt);
  const Json jx = metrics::evaluate_view(d.sensor, mix, gt);
  for (const char* k : kAltDepthKeys) {
    m[std::string("median_") + k] = jm.at(k);
    m[std::string("mix_") + k] = jx.at(k);
  }
  m["mix_median_fraction"] = double(mixed) / double(std::max<size_t>(1, pred.size()));
  m["opacity_mean"] = returning > 0 ? Json(opacity / double(returning)) : Json(nullptr);
}

void add_view(ViewSet& vs, std::vector<Json>& views, const Dataset& d, int f, RangeImage pred,
              const DepthStats* stats = nullptr) {
  Json m = metrics::evaluate_view(d.sensor, pred, d.frames[size_t(f)].image);
  if (stats) add_depth_variants(m, d, f, pred, *stats);
  views.push_back(m);
  Json row = Json{{"frame", d.frames[size_t(f)].id}};
  for (auto it = m.begin(); it != m.end(); ++it) row[it.key()] = it.value();
  vs.per_frame.push_back(row);
  vs.images.push_back(std::move(pred));
}

}  // namespace

ViewSet evaluate_model(LidarNerfModel& model, const Dataset& d, const Scene& scene,
                       int chunk_rays, const std::vector<Pose>& T_world_lidar,
                       FastRenderer* fast, const RayDropStage* refine, BakedRenderer* baked) {
  if (d.split.test.empty()) throw Error("dataset " + d.name + ": no test frames to evaluate");
  require(T_world_lidar.size() == d.frames.size(),
          "evaluate_model: " + std::to_string(T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  ViewSet vs;
  std::vector<Json> views;
  for (int f : d.split.test) {
    DepthStats stats;
    RangeImage pred = fast    ? fast->render(T_world_lidar[size_t(f)], f)
                      : baked ? baked->render(T_world_lidar[size_t(f)], scene, &stats)
                              : render_view(model, scene, T_world_lidar[size_t(f)], chunk_rays, f,
                                            nullptr, &stats);
    if (refine) refine->apply(pred);
    add_view(vs, views, d, f, std::move(pred), fast ? nullptr : &stats);
  }
  vs.mean = metrics::mean_metrics(views);
  return vs;
}

ViewSet evaluate_naive(const Dataset& d) { return evaluate_naive(d, gt_poses(d)); }

ViewSet evaluate_naive(const Dataset& d, const std::vector<Pose>& T_world_lidar) {
  if (d.split.test.empty()) throw Error("dataset " + d.name + ": no test frames to evaluate");
  require(T_world_lidar.size() == d.frames.size(),
          "evaluate_naive: " + std::to_string(T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  std::vector<Pose> poses;
  std::vector<const std::vector<PointXYZI>*> scans;
  for (int f : d.split.train) {
    poses.push_back(T_world_lidar[size_t(f)]);
    scans.push_back(&d.frames[size_t(f)].points);
  }
  ViewSet vs;
  std::vector<Json> views;
  for (int f : d.split.test)
    add_view(vs, views, d, f,
             metrics::naive_baseline_view(d.sensor, poses, scans, T_world_lidar[size_t(f)]));
  vs.mean = metrics::mean_metrics(views);
  return vs;
}

}  // namespace sgnlf::pipeline
