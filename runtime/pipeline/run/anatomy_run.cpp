// anatomy_run (see anatomy_run.hpp).
#include "pipeline/run/anatomy_run.hpp"

#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "datasets/protocol.hpp"
#include "io/marked_depth_picture.hpp"
#include "metrics/anatomy.hpp"
#include "metrics/anatomy_json.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/image_metrics.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/run/evaluate.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;
namespace {

// Every training scan's points in the world frame under `T_world_lidar` (one pose per frame).
std::vector<geometry::Point3f> training_points_world(const Dataset& d,
                                                     const std::vector<Pose>& T_world_lidar) {
  std::vector<geometry::Point3f> pts;
  for (int f : d.split.train) {
    const Eigen::Isometry3f T = T_world_lidar[size_t(f)].cast<float>();
    for (const PointXYZI& p : d.frames[size_t(f)].points) {
      const geometry::Point3f p_world = T * geometry::Point3f(p.x, p.y, p.z);
      if (p_world.allFinite()) pts.push_back(p_world);
    }
  }
  return pts;
}

std::vector<uint8_t> marks_of(const metrics::ViewAnatomy& a) {
  std::vector<uint8_t> m(a.pixel_case.size(), io::kMarkNone);
  for (size_t i = 0; i < m.size(); ++i) {
    if (a.pixel_case[i] == uint8_t(metrics::ReturnCase::false_return)) m[i] = io::kMarkFalseReturn;
    if (a.pixel_case[i] == uint8_t(metrics::ReturnCase::missed)) m[i] = io::kMarkMissedReturn;
  }
  return m;
}

}  // namespace

Json anatomy_run(LoadedRun& run, const std::string& out_dir, const TestViewImages* rendered) {
  const Dataset& d = *run.dataset;
  TestViewImages own;
  if (!rendered) {
    own.model = evaluate_model(*run.model, d, *run.scene, run.manifest.config.schedule.render_chunk_rays,
                               run.T_world_lidar, nullptr, run.ray_drop.get()).images;
  }
  // The naive baseline's poses, as eval_run's: the reference, else the run's own.
  const std::vector<Pose> poses = d.has_reference_poses ? gt_poses(d) : run.T_world_lidar;
  if (!rendered) own.naive = evaluate_naive(d, poses).images;
  const TestViewImages& views = rendered ? *rendered : own;
  require(views.model.size() == d.split.test.size() && views.naive.size() == d.split.test.size(),
          "anatomy_run: " + std::to_string(views.model.size()) + " model and " +
              std::to_string(views.naive.size()) + " naive views for " +
              std::to_string(d.split.test.size()) + " test frames of " + d.name);

  const std::vector<geometry::Point3f> train_world = training_points_world(d, poses);
  require(!train_world.empty(), "anatomy_run: the training scans of " + d.name + " hold no points");
  const geometry::KdTree tree(train_world);
  const fs::path pictures = fs::path(out_dir) / "anatomy";
  fs::create_directories(pictures);
  io::RangePictureOptions po;
  po.max_range_m = d.sensor.max_range_m;

  std::vector<Json> model_views, naive_views;
  Json model_frames = Json::array(), naive_frames = Json::array(), files = Json::array();
  for (size_t k = 0; k < d.split.test.size(); ++k) {
    const Frame& fr = d.frames[size_t(d.split.test[k])];
    const metrics::TrainingPoints tp{&tree, poses[size_t(d.split.test[k])]};
    const metrics::ViewAnatomy am = metrics::view_anatomy(d.sensor, views.model[k], fr.image, &tp);
    const metrics::ViewAnatomy an = metrics::view_anatomy(d.sensor, views.naive[k], fr.image, &tp);
    model_views.push_back(metrics::anatomy_json(am));
    naive_views.push_back(metrics::anatomy_json(an));
    Json mrow = model_views.back(), nrow = naive_views.back();
    mrow["frame"] = nrow["frame"] = fr.id;
    model_frames.push_back(std::move(mrow));
    naive_frames.push_back(std::move(nrow));
    const RangeImage model_masked = masked_prediction(views.model[k]);
    const RangeImage naive_masked = masked_prediction(views.naive[k]);
    const std::string png = "anatomy/" + std::to_string(fr.id) + ".png";  // relative to out_dir
    io::write_png((fs::path(out_dir) / png).string(), io::marked_depth_picture({{&model_masked, marks_of(am)},
                                                 {&naive_masked, marks_of(an)},
                                                 {&fr.image, {}}},
                                                po));
    files.push_back(png);
  }
  Json j{{"method", run.manifest.method},
         {"preset", run.manifest.preset},
         {"dataset", d.name},
         {"step", run.step},
         {"train_points", train_world.size()},
         {"train_poses", d.has_reference_poses ? "reference" : "run"},
         {"model", {{"mean", metrics::mean_metrics(model_views)}, {"per_frame", model_frames}}},
         {"naive_baseline",
          {{"mean", metrics::mean_metrics(naive_views)}, {"per_frame", naive_frames}}},
         {"pictures", files},  // relative to the folder of anatomy.json
         {"picture_panels", {"model (rendered, masked at p > 0.5)", "naive baseline (nearest training scan)",
                             "observed scan"}},
         {"picture_colours", {{"false_return", "magenta"}, {"missed_return", "white"},
                              {"depth", "turbo on log(1 + r) / log(1 + max range)"}}}};
  write_json_file((fs::path(out_dir) / "anatomy.json").string(), j);
  return j;
}

}  // namespace sgnlf::pipeline
