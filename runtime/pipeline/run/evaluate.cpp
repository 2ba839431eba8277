// evaluate_model / evaluate_naive (see evaluate.hpp).
#include "pipeline/run/evaluate.hpp"

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/protocol.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/naive_baseline.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/run/ray_drop_stage.hpp"

namespace sgnlf::pipeline {
namespace {

void add_view(ViewSet& vs, std::vector<Json>& views, const Dataset& d, int f, RangeImage pred) {
  Json m = metrics::evaluate_view(d.sensor, pred, d.frames[size_t(f)].image);
  views.push_back(m);
  Json row = Json{{"frame", d.frames[size_t(f)].id}};
  for (auto it = m.begin(); it != m.end(); ++it) row[it.key()] = it.value();
  vs.per_frame.push_back(row);
  vs.images.push_back(std::move(pred));
}

}  // namespace

ViewSet evaluate_model(LidarNerfModel& model, const Dataset& d, const Scene& scene,
                       int chunk_rays, const std::vector<Pose>& T_world_lidar,
                       FastRenderer* fast, const RayDropStage* refine) {
  if (d.split.test.empty()) throw Error("dataset " + d.name + ": no test frames to evaluate");
  require(T_world_lidar.size() == d.frames.size(),
          "evaluate_model: " + std::to_string(T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  ViewSet vs;
  std::vector<Json> views;
  for (int f : d.split.test) {
    RangeImage pred = fast ? fast->render(T_world_lidar[size_t(f)], f)
                           : render_view(model, scene, T_world_lidar[size_t(f)], chunk_rays, f);
    if (refine) refine->apply(pred);
    add_view(vs, views, d, f, std::move(pred));
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
