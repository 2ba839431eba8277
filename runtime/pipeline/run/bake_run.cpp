// bake_run (see bake_run.hpp).
#include "pipeline/run/bake_run.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace sgnlf::pipeline {

bake::BakedScene bake_run(LoadedRun& run, const std::string& run_dir, const bake::BakeConfig& cfg,
                          bake::BakeStats* stats) {
  if (run.model->temporal())
    throw ConfigError("bake: " + run_dir + " holds a 4D field (" + run.manifest.method +
                      "); baking bakes a static field (a 4D one would need a bake per frame time)");
  const Scene& sc = *run.scene;
  const Dataset& d = *run.dataset;
  bake::BakeInput in;
  // The training returns and origins in the world frame, metres, under the run's poses; not
  // the pose-free methods' test frames (in `train` for their poses only).
  for (int k : sc.train) {
    if (std::find(sc.pose_only.begin(), sc.pose_only.end(), k) != sc.pose_only.end()) continue;
    const RangeImage& img = d.frames[size_t(k)].image;
    const Pose& T = run.T_world_lidar[size_t(k)];
    const Eigen::Vector3d o = T.translation();
    for (int a = 0; a < 3; ++a) in.origins_m.push_back(float(o[a]));
    for (size_t p = 0; p < img.size(); ++p) {
      const float r = img.range[p];
      if (!(r > 0.0f)) continue;
      const Eigen::Vector3d dir(sc.directions[3 * p], sc.directions[3 * p + 1], sc.directions[3 * p + 2]);
      const Eigen::Vector3d w = T * (dir * double(r));
      for (int a = 0; a < 3; ++a) in.returns_m.push_back(float(w[a]));
    }
  }
  const auto& rc = run.manifest.config.render;
  in.near_m = rc.near_m, in.far_m = rc.far_m;
  const double s = sc.norm.scale;
  const Eigen::Vector3d c = sc.norm.center;
  // World metres → the normalised box, clamped to it as the renderer clamps its samples.
  const auto normalise = [&](const std::vector<float>& x_m) {
    std::vector<float> x(x_m.size());
    for (size_t p = 0; p < x.size(); ++p)
      x[p] = std::clamp(float((double(x_m[p]) - c[long(p % 3)]) * s), -1.0f, 1.0f);
    return x;
  };
  LidarNerfModel& model = *run.model;
  bake::FieldProbe probe;
  probe.batch = model.sample_capacity();
  const float log_s = float(std::log(s));
  probe.density = [&](const std::vector<float>& x_m, int n) {
    std::vector<float> l = model.density_logits(normalise(x_m), n);
    for (float& v : l) v += log_s;  // σ per metre = σ per normalised unit · s
    return l;
  };
  probe.head = [&](const std::vector<float>& x_m, const std::vector<float>& dir, int n) {
    return model.head_at(normalise(x_m), dir, n);
  };
  bake::BakeStats st;
  bake::BakedScene scene = bake::bake_field(cfg, in, probe, &st);
  scene.provenance = Json{{"run", run_dir},
                          {"method", run.manifest.method},
                          {"preset", run.manifest.preset},
                          {"dataset", d.name},
                          {"step", run.step},
                          {"config", cfg.to_json()},
                          {"stats", st.to_json()}};
  if (stats) *stats = st;
  return scene;
}

}  // namespace sgnlf::pipeline
