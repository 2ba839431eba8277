// LiDAR4D's ray-drop refinement as a stage of the method (method.md §2; LiDAR4D's
// Trainer.refine()): after the field's training the training frames are rendered (return
// probability, intensity, range in metres) and the U-Net (refine/ray_drop_unet.hpp) learns their
// observed return masks (refine/ray_drop_training.hpp: full batch, box dropout, one-cycle lr);
// afterwards every render of the run (eval, render, render_poses) has its return probability
// replaced by the U-Net's inference output on it. The config is lidar4d.refine
// (config/lidar4d_config.hpp); the trained parameters live in <run>/ray_drop_unet.bin.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "core/config_fwd.hpp"
#include "datasets/dataset.hpp"
#include "pipeline/config/train_config.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/scene.hpp"
#include "refine/ray_drop_unet.hpp"

namespace sgnlf::pipeline {

// The training frames (indices into Dataset::frames) the stage renders: all of `train` for
// frames = 0 or frames >= its size, else `frames` evenly spaced over it (rounded to the nearest),
// the first and the last included; frames = 1 takes the first.
std::vector<int> ray_drop_frames(const std::vector<int>& train, int frames);

// <run>/ray_drop_unet.bin
std::string ray_drop_unet_path(const std::string& run_dir);

class RayDropStage {
 public:
  // A U-Net at its initial parameters (cfg.unet.seed).
  RayDropStage(cl::Runtime& rt, const RayDropRefinementConfig& cfg);
  const RayDropRefinementConfig& config() const { return cfg_; }

  // Renders the training frames (ray_drop_frames) with `model` at T_world_lidar[f] (metres, one
  // per dataset frame) and trains the U-Net from its initial parameters against the frames'
  // return labels. Returns {frames (frame ids), steps, initial_bce, final_bce, render_seconds,
  // train_seconds}; the BCEs are the inference-mode losses on the training frames.
  Json train(LidarNerfModel& model, const Scene& scene, const Dataset& d,
             const std::vector<Pose>& T_world_lidar, int chunk_rays);

  // The U-Net's parameters in the checkpoint format (train/checkpoint.hpp: magic, version,
  // checksum, atomic write), under the hash of the U-Net config. load() refuses a file saved
  // under another U-Net config or with another parameter count (ConfigError naming the file and
  // both); a missing or corrupt file is an IoError naming it.
  void save(const std::string& path) const;
  void load(const std::string& path);

  // Replaces pred.ray_drop by the U-Net's return probability on (pred.ray_drop,
  // pred.intensity, pred.range): inference, no augmentation, deterministic. Range and intensity
  // stay as they are. Logically const: the parameters do not change (the net's work buffers do).
  void apply(RangeImage& pred) const;

 private:
  RayDropRefinementConfig cfg_;
  std::unique_ptr<refine::RayDropUNet> net_;
};

// The stage of a finished training run (train_run): trains it on the renders of `model` at the
// evaluation's sampling (render.eval_samples / eval_importance, as load_run renders) and saves
// ray_drop_unet_path(run_dir); when that file is there already (a finished run resumed), loads
// it instead. Returns the summary's "ray_drop_refinement" (the training summary plus "file", or
// {file, reused: true}).
Json refine_finished_run(cl::Runtime& rt, const TrainConfig& c, LidarNerfModel& model,
                         const Scene& scene, const Dataset& d,
                         const std::vector<Pose>& T_world_lidar, const std::string& run_dir);

}  // namespace sgnlf::pipeline
