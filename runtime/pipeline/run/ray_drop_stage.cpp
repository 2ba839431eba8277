// RayDropStage (see ray_drop_stage.hpp).
#include "pipeline/run/ray_drop_stage.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "pipeline/model/render_view.hpp"
#include "pipeline/train/checkpoint.hpp"
#include "refine/ray_drop_training.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;
namespace {

constexpr const char* kParams = "ray_drop_unet.params";

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The U-Net's input channels of one view at out[p * 3 + c]: return probability, intensity,
// range in metres (RayDropUNet::kInputChannels).
void pack_view(const RangeImage& r, float* out) {
  for (size_t p = 0; p < r.size(); ++p) {
    out[3 * p + 0] = r.ray_drop[p];
    out[3 * p + 1] = r.intensity[p];
    out[3 * p + 2] = r.range[p];
  }
}

uint64_t unet_hash(const refine::RayDropUNetConfig& c) { return fnv1a64(c.to_json().dump()); }

// The config as load_run renders with it: the evaluation's sampling where the config sets one.
TrainConfig with_eval_sampling(TrainConfig c) {
  if (c.render.eval_samples > 0) c.render.n_samples = c.render.eval_samples;
  if (c.render.eval_importance >= 0) c.render.n_importance = c.render.eval_importance;
  return c;
}

}  // namespace

std::vector<int> ray_drop_frames(const std::vector<int>& train, int frames) {
  const int n = int(train.size());
  if (frames <= 0 || frames >= n) return train;
  if (frames == 1) return {train.front()};
  std::vector<int> out;
  for (int i = 0; i < frames; ++i)  // round(i · (n − 1) / (frames − 1)), strictly increasing
    out.push_back(train[size_t((2L * i * (n - 1) + (frames - 1)) / (2L * (frames - 1)))]);
  return out;
}

std::string ray_drop_unet_path(const std::string& run_dir) {
  return (fs::path(run_dir) / "ray_drop_unet.bin").string();
}

RayDropStage::RayDropStage(cl::Runtime& rt, const RayDropRefinementConfig& cfg)
    : cfg_(cfg), net_(std::make_unique<refine::RayDropUNet>(rt, cfg.unet)) {}

Json RayDropStage::train(LidarNerfModel& model, const Scene& scene, const Dataset& d,
                         const std::vector<Pose>& T_world_lidar, int chunk_rays) {
  require(T_world_lidar.size() == d.frames.size(),
          "ray-drop refinement: " + std::to_string(T_world_lidar.size()) + " poses for " +
              std::to_string(d.frames.size()) + " frames");
  const std::vector<int> frames = ray_drop_frames(d.split.train, cfg_.frames);
  if (frames.empty())
    throw Error("dataset " + d.name + ": no training frames to train the ray-drop U-Net on");
  const int n = int(frames.size()), h = scene.sensor.height, w = scene.sensor.width;
  const size_t hw = size_t(h) * size_t(w);
  net_->check_size(h, w);
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<float> inputs(size_t(n) * hw * refine::RayDropUNet::kInputChannels), masks(size_t(n) * hw);
  Json ids = Json::array();
  Progress renders("ray-drop refinement: render", n);
  for (int k = 0; k < n; ++k) {
    const int f = frames[size_t(k)];
    const RangeImage& gt = d.frames[size_t(f)].image;
    if (gt.height != h || gt.width != w)
      throw Error("dataset " + d.name + ": frame " + std::to_string(d.frames[size_t(f)].id) +
                  " has a " + std::to_string(gt.height) + " x " + std::to_string(gt.width) +
                  " range image, the sensor renders " + std::to_string(h) + " x " +
                  std::to_string(w));
    const RangeImage pred = render_view(model, scene, T_world_lidar[size_t(f)], chunk_rays, f);
    pack_view(pred, &inputs[size_t(k) * hw * refine::RayDropUNet::kInputChannels]);
    std::copy(gt.ray_drop.begin(), gt.ray_drop.end(), masks.begin() + long(size_t(k) * hw));
    ids.push_back(d.frames[size_t(f)].id);
    renders.update(k + 1);
  }
  renders.finish();
  const double render_s = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  cl::Runtime& rt = net_->runtime();
  net_->reset();
  Progress steps("ray-drop refinement: U-Net", cfg_.unet.steps);
  const refine::RayDropTrainResult r =
      refine::train_ray_drop(*net_, cl::Buffer::from(rt, inputs), cl::Buffer::from(rt, masks), n,
                             h, w, [&](int done) { steps.update(done); });
  steps.finish();
  return Json{{"frames", ids},
              {"steps", r.steps},
              {"initial_bce", r.initial_loss},
              {"final_bce", r.final_loss},
              {"render_seconds", render_s},
              {"train_seconds", seconds_since(t1)}};
}

void RayDropStage::save(const std::string& path) const {
  Checkpoint ck;
  ck.step = cfg_.unet.steps;
  ck.seed = cfg_.unet.seed;
  ck.config_hash = unet_hash(cfg_.unet);
  ck.arrays.emplace_back(kParams, net_->params().read_vec<float>(net_->n_params()));
  save_checkpoint(path, ck);
}

void RayDropStage::load(const std::string& path) {
  const Checkpoint ck = load_checkpoint(path);
  if (ck.config_hash != unet_hash(cfg_.unet))
    throw ConfigError(path + ": the ray-drop U-Net there was trained under U-Net config " +
                      hex64(ck.config_hash) + ", this run's lidar4d.refine.unet is " +
                      hex64(unet_hash(cfg_.unet)) + " (" + cfg_.unet.to_json().dump() + ")");
  const std::vector<float>* params = nullptr;
  for (const auto& [name, v] : ck.arrays)
    if (name == kParams) params = &v;
  if (!params) throw IoError(path + ": no array '" + kParams + "' (not a ray-drop U-Net file)");
  if (params->size() != net_->n_params())
    throw ConfigError(path + ": " + std::to_string(params->size()) +
                      " U-Net parameters, this run's U-Net has " + std::to_string(net_->n_params()));
  net_->params().write_vec(*params);
}

void RayDropStage::apply(RangeImage& pred) const {
  std::vector<float> x(pred.size() * refine::RayDropUNet::kInputChannels);
  pack_view(pred, x.data());
  cl::Runtime& rt = net_->runtime();
  cl::Buffer probs(rt, pred.size() * sizeof(float));
  net_->forward(cl::Buffer::from(rt, x), 1, pred.height, pred.width, probs);
  pred.ray_drop = probs.read_vec<float>(pred.size());
}

Json refine_finished_run(cl::Runtime& rt, const TrainConfig& c, LidarNerfModel& model,
                         const Scene& scene, const Dataset& d,
                         const std::vector<Pose>& T_world_lidar, const std::string& run_dir) {
  require(c.lidar4d.has_value(), "ray-drop refinement: the config has no lidar4d section");
  const std::string file = ray_drop_unet_path(run_dir);
  RayDropStage stage(rt, c.lidar4d->refine.value());
  if (fs::exists(file)) {
    stage.load(file);  // the run's own file: a damaged or foreign one is an error, not retrained
    log::info("ray-drop refinement: reusing ", file);
    return Json{{"file", file}, {"reused", true}};
  }
  // Rendered as evaluation renders (its sampling), so the U-Net sees the inputs it will refine.
  const TrainConfig e = with_eval_sampling(c);
  std::unique_ptr<LidarNerfModel> eval_model;
  if (e.render.n_samples != c.render.n_samples || e.render.n_importance != c.render.n_importance) {
    eval_model = std::make_unique<LidarNerfModel>(rt, e, float(scene.norm.scale), model_capacity(e));
    eval_model->set_params(model.params());
  }
  Json j = stage.train(eval_model ? *eval_model : model, scene, d, T_world_lidar,
                       c.schedule.render_chunk_rays);
  stage.save(file);
  log::info("ray-drop refinement: ", j.at("frames").size(), " frames rendered in ",
            j.at("render_seconds").get<double>(), " s, ", j.at("steps").get<int>(),
            " U-Net steps in ", j.at("train_seconds").get<double>(), " s, BCE ",
            j.at("initial_bce").get<double>(), " -> ", j.at("final_bce").get<double>(), "; ",
            file);
  j["file"] = file;
  return j;
}

}  // namespace sgnlf::pipeline
