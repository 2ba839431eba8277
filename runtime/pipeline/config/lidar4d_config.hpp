// Configuration of LiDAR4D (method.md §2), the config's "lidar4d" section: the 4D encoder that
// replaces the hash grid (field/lidar4d_encoder_config.hpp), the learning rate of the networks
// beside the encodings', the Chamfer term on ray points, the scene-flow supervision and the
// ray-drop U-Net refinement after training.
// Present only in the configs of methods built on the 4D field (ConfigSections::lidar4d,
// methods/), so other methods' config hashes do not change.
#pragma once
#include <optional>

#include "core/config_fwd.hpp"
#include "field/lidar4d_encoder_config.hpp"
#include "refine/ray_drop_unet_config.hpp"

namespace sgnlf::pipeline {

// LiDAR4D's supervision of the flow field (model/runner.py; render/scene_flow_loss.hpp): the
// ground-removed points of the batch's frame, moved by the predicted flow, against those of
// the frames `steps` away; the flow of the ground points pulled to zero.
struct FlowSupervisionConfig {
  double weight = 0.01;          // on the summed Chamfer terms (LiDAR4D: 0.01)
  double ground_weight = 0.001;  // on Σ|flow| of the ground points
  int steps = 1;                 // 1: frames k ± 1 (LiDAR4D's released code); 2: also k ± 2
  int every = 1;                 // one flow step every `every` training steps
  int points = 2048;             // ground-removed points per frame (a fixed-seed subsample)
  int ground_points = 256;       // ground points per frame for the zero-flow term
  // The ground of a scan: the densest height bin (bin_m) in the lower half of the scan's
  // returns within range_m in the sensor frame; a point is ground below that height + margin_m.
  double ground_bin_m = 0.1;
  double ground_margin_m = 0.3;
  double ground_range_m = 30.0;
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("weight", s.weight, 0.0, 1e6);
    v("ground_weight", s.ground_weight, 0.0, 1e6);
    v("steps", s.steps, 1, 2);
    v("every", s.every, 1, 1000000);
    v("points", s.points, 16, 1 << 20);
    v("ground_points", s.ground_points, 0, 1 << 20);
    v("ground_bin_m", s.ground_bin_m, 0.01, 10.0);
    v("ground_margin_m", s.ground_margin_m, 0.0, 10.0);
    v("ground_range_m", s.ground_range_m, 1.0, 1000.0);
  }
};

// LiDAR4D's ray-drop refinement (Trainer.refine(); run/ray_drop_stage.hpp): after the field's
// training, the U-Net learns the training frames' return masks from their rendered (return
// probability, intensity, depth) images; every later render's return probability is its output.
struct RayDropRefinementConfig {
  // Training frames rendered for it: 0 = every one (LiDAR4D), else that many evenly spaced over
  // the training split, the first and the last included.
  int frames = 0;
  refine::RayDropUNetConfig unet;  // LiDAR4D's U-Net and schedule by default
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("frames", s.frames, 0, 1000000);
    v.object("unet", s.unet);
  }
};

struct Lidar4DConfig {
  field::Lidar4DEncoderConfig encoder;
  // The density and LiDAR-head MLPs and the flow field learn at lr · network_lr_scale, the
  // encodings at lr (LiDAR4D: 1e-2 and 1e-3).
  double network_lr_scale = 0.1;
  // LiDAR4D's Chamfer term between the predicted and observed ray endpoints of a batch
  // (render/chamfer_loss.hpp, in metres², mean over rays); 0 turns it off.
  double chamfer_weight = 1.0;
  // LiDAR4D's separate intensity and ray-drop MLPs (model/lidar4d.py: intensity_net and
  // raydrop_net, each field.head_layers layers of field.head_hidden on the same input): the
  // head becomes one field::Mlp of two towers (MlpSpec::towers), each field.head_hidden wide,
  // which computes exactly two separate networks. false: LiDAR-NeRF's one head, two outputs.
  bool separate_heads = true;
  // Ray-drop label smoothing (LiDAR4D's smooth_factor 0.2): the return term's label is
  // clamped to [s, 1 − s]; the masks of the depth and intensity terms stay 0/1.
  double ray_drop_label_smoothing = 0.2;
  // Optional sections, on exactly when present in the JSON (LiDAR4D's, so on in a default one).
  std::optional<FlowSupervisionConfig> flow = FlowSupervisionConfig{};
  std::optional<RayDropRefinementConfig> refine = RayDropRefinementConfig{};
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.object("encoder", s.encoder);
    v("network_lr_scale", s.network_lr_scale, 0.0, 10.0);
    v("chamfer_weight", s.chamfer_weight, 0.0, 1e6);
    v("separate_heads", s.separate_heads);
    v("ray_drop_label_smoothing", s.ray_drop_label_smoothing, 0.0, 0.49);
    v.optional("flow", s.flow);
    v.optional("refine", s.refine);
  }

  void validate(const std::string& where) const;
  static Lidar4DConfig from_json(ConfigReader& r);  // reads "lidar4d"; errors name r.where()
  void to_json(Json& j) const;                      // adds the "lidar4d" section
};

}  // namespace sgnlf::pipeline
