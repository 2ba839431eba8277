// RenderConfig presets, validation and JSON.
#include "render/render_config.hpp"

namespace sgnlf::render {

RenderConfig RenderConfig::preset(const std::string& dataset) {
  RenderConfig c;
  if (dataset == "kitti360") {
    c.weights = {1000.0f, 1.0f, 10.0f, 100.0f};
  } else if (dataset == "nuscenes") {
    c.weights = {1000.0f, 4.5f, 100.0f, 100.0f};
  } else {
    throw ConfigError("render preset: unknown dataset '" + dataset +
                      "' (expected kitti360 or nuscenes)");
  }
  return c;
}

void RenderConfig::validate(const std::string& where) const {
  check_range(where, "near_m", near_m, 0.0f, 1e4f);
  check_range(where, "far_m", far_m, 0.0f, 1e5f);
  if (!(far_m > near_m))
    throw ConfigError(where + ": 'far_m' = " + std::to_string(far_m) +
                      " must exceed 'near_m' = " + std::to_string(near_m));
  check_range(where, "n_samples", n_samples, 1, 1 << 16);
  check_range(where, "n_importance", n_importance, 0, 1 << 16);
  check_range(where, "eval_samples", eval_samples, 0, 1 << 16);
  check_range(where, "eval_importance", eval_importance, -1, 1 << 16);
  if (eval_depth != "expected" && eval_depth != "median")
    throw ConfigError(where + ": 'eval_depth' = '" + eval_depth +
                      "' (expected \"expected\" or \"median\")");
  check_range(where, "stop_transmittance", stop_transmittance, 0.0f, 0.5f);
  check_range(where, "coarse_waves", coarse_waves, 1, n_samples);
  check_range(where, "head_weight_threshold", head_weight_threshold, 0.0f, 0.1f);
  if (head_weight_threshold > 0.0f && !(stop_transmittance > 0.0f))
    throw ConfigError(where + ": 'head_weight_threshold' = " +
                      std::to_string(head_weight_threshold) +
                      " needs early termination ('stop_transmittance' > 0)");
  if (coarse_waves > 1 && !(stop_transmittance > 0.0f))
    throw ConfigError(where + ": 'coarse_waves' = " + std::to_string(coarse_waves) +
                      " needs early termination ('stop_transmittance' > 0)");
  check_range(where, "weights.depth", weights.depth, 0.0f, 1e9f);
  check_range(where, "weights.ret", weights.ret, 0.0f, 1e9f);
  check_range(where, "weights.intensity", weights.intensity, 0.0f, 1e9f);
  check_range(where, "weights.grad", weights.grad, 0.0f, 1e9f);
  check_range(where, "patch_rows", patch_rows, 1, 256);
  check_range(where, "patch_cols", patch_cols, 1, 256);
  if (patch_rows * patch_cols < 2)
    throw ConfigError(where + ": a patch of 'patch_rows' x 'patch_cols' = 1 x 1 has no pairs");
  check_range(where, "grad_clip_m", grad_clip_m, 0.0f, 1e5f);
}

RenderConfig RenderConfig::from_json(const Json& j, const std::string& where, RenderConfig c) {
  ConfigReader r(j, where);
  r.get("near_m", c.near_m).get("far_m", c.far_m).get("n_samples", c.n_samples);
  r.get("n_importance", c.n_importance).get("jitter", c.jitter);
  r.get("eval_samples", c.eval_samples).get("eval_importance", c.eval_importance);
  r.get("stop_transmittance", c.stop_transmittance).get("eval_depth", c.eval_depth);
  r.get("coarse_waves", c.coarse_waves).get("head_weight_threshold", c.head_weight_threshold);
  r.get("patch_rows", c.patch_rows).get("patch_cols", c.patch_cols);
  r.get("grad_l1", c.grad_l1).get("grad_clip_m", c.grad_clip_m);
  if (r.has("weights")) {
    auto w = r.child("weights");
    w.get("depth", c.weights.depth).get("ret", c.weights.ret);
    w.get("intensity", c.weights.intensity).get("grad", c.weights.grad);
    w.finish();
  }
  r.finish();
  c.validate(where);
  return c;
}

RenderConfig RenderConfig::from_json(const Json& j, const std::string& where) {
  return from_json(j, where, RenderConfig());
}

Json RenderConfig::to_json() const {
  Json j{{"near_m", near_m},
              {"far_m", far_m},
              {"n_samples", n_samples},
              {"n_importance", n_importance},
              {"jitter", jitter},
              {"patch_rows", patch_rows},
              {"patch_cols", patch_cols},
              {"grad_l1", grad_l1},
              {"grad_clip_m", grad_clip_m},
              {"weights",
               {{"depth", weights.depth},
                {"ret", weights.ret},
                {"intensity", weights.intensity},
                {"grad", weights.grad}}}};
  if (eval_samples != 0) j["eval_samples"] = eval_samples;
  if (eval_importance != -1) j["eval_importance"] = eval_importance;
  if (eval_depth != "expected") j["eval_depth"] = eval_depth;
  if (stop_transmittance != 0.0f) j["stop_transmittance"] = stop_transmittance;
  if (coarse_waves != 1) j["coarse_waves"] = coarse_waves;
  if (head_weight_threshold != 0.0f) j["head_weight_threshold"] = head_weight_threshold;
  return j;
}

}  // namespace sgnlf::render
