// PoseFreeConfig: strict JSON reading, writing and validation (see pose_free_config.hpp).
#include "pipeline/pose_free_config.hpp"

#include <cmath>

namespace sgnlf::pipeline {

int GeometricScheduleConfig::steps_at(long epoch, double progress) const {
  if (!enabled) return 0;
  if (epoch == 0) return first_steps;
  if (progress >= stop_progress) return 0;
  return int(std::lround(steps_per_epoch * (1.0 - progress / stop_progress)));
}

void PoseFreeConfig::validate(const std::string& w) const {
  if (poses.init != "gt" && poses.init != "noisy" && poses.init != "identity" &&
      poses.init != "odometry")
    throw ConfigError(w + ".poses: 'init' = \"" + poses.init +
                      "\" is not one of \"gt\", \"noisy\", \"identity\", \"odometry\"");
  check_range(w + ".poses", "sigma_rot_rad", poses.sigma_rot_rad, 0.0, 3.2);
  check_range(w + ".poses", "sigma_trans_m", poses.sigma_trans_m, 0.0, 1e3);
  const std::string o = w + ".pose_optim";
  check_range(o, "lr_rot", pose_optim.lr_rot, 0.0, 1.0);
  check_range(o, "lr_trans", pose_optim.lr_trans, 0.0, 1.0);
  check_range(o, "final_factor", pose_optim.final_factor, 1e-6, 1.0);
  check_range(o, "identity_lr_factor", pose_optim.identity_lr_factor, 1e-3, 1e3);
  check_range(o, "start_step", pose_optim.start_step, 0L, 1L << 40);
  check_range(o, "beta1", pose_optim.beta1, 0.0, 0.999999);
  check_range(o, "beta2", pose_optim.beta2, 0.0, 0.999999999);
  check_range(o, "eps", pose_optim.eps, 1e-30, 1.0);
  const std::string r = w + ".reweight";
  check_range(r, "fraction", reweight.fraction, 0.0, 1.0);
  check_range(r, "factor", reweight.factor, 0.0, 1.0);
  check_range(r, "ema", reweight.ema, 0.0, 0.999999);
  const std::string g = w + ".geometric";
  check_range(g, "points_per_frame", geometric.points_per_frame, 16, 1 << 22);
  check_range(g, "first_steps", geometric.first_steps, 0, 1 << 20);
  check_range(g, "steps_per_epoch", geometric.steps_per_epoch, 0.0, 1e6);
  check_range(g, "stop_progress", geometric.stop_progress, 0.0, 1.0);
  check_range(g, "lr_rot", geometric.lr_rot, 0.0, 1.0);
  check_range(g, "lr_trans", geometric.lr_trans, 0.0, 100.0);
  check_range(g, "lr_final", geometric.lr_final, 1e-6, 1.0);
  if (geometric.tau_scale != -1.0) check_range(g, "tau_scale", geometric.tau_scale, 0.0, 100.0);
  if (geometric.edge_offsets.empty()) throw ConfigError(g + ": 'edge_offsets' is empty");
  if (geometric.residual != "point_to_point" && geometric.residual != "point_to_plane")
    throw ConfigError(g + ": 'residual' = \"" + geometric.residual +
                      "\" is not one of \"point_to_point\", \"point_to_plane\"");
  for (int k : geometric.edge_offsets) check_range(g, "edge_offsets[]", k, 1, 1000);
  check_range(g, "threads", geometric.threads, 1, 256);
}

PoseFreeConfig PoseFreeConfig::from_json(ConfigReader& r) {
  PoseFreeConfig c;
  {
    auto p = r.child("poses");
    p.get("init", c.poses.init).get("noise_seed", c.poses.noise_seed);
    p.get("sigma_rot_rad", c.poses.sigma_rot_rad).get("sigma_trans_m", c.poses.sigma_trans_m);
    p.finish();
  }
  {
    auto o = r.child("pose_optim");
    auto& po = c.pose_optim;
    o.get("optimize", po.optimize).get("lr_rot", po.lr_rot).get("lr_trans", po.lr_trans);
    o.get("final_factor", po.final_factor).get("identity_lr_factor", po.identity_lr_factor);
    o.get("beta1", po.beta1).get("beta2", po.beta2).get("eps", po.eps);
    o.get("start_step", po.start_step);
    o.finish();
  }
  {
    auto rw = r.child("reweight");
    rw.get("enabled", c.reweight.enabled).get("fraction", c.reweight.fraction);
    rw.get("factor", c.reweight.factor).get("ema", c.reweight.ema);
    rw.finish();
  }
  r.get("coarse_to_fine", c.coarse_to_fine);
  {
    auto g = r.child("geometric");
    auto& gc = c.geometric;
    g.get("enabled", gc.enabled).get("points_per_frame", gc.points_per_frame);
    g.get("edge_offsets", gc.edge_offsets).get("first_steps", gc.first_steps);
    g.get("steps_per_epoch", gc.steps_per_epoch).get("stop_progress", gc.stop_progress);
    g.get("tau_scale", gc.tau_scale).get("lr_rot", gc.lr_rot).get("lr_trans", gc.lr_trans);
    g.get("lr_final", gc.lr_final).get("residual", gc.residual);
    g.get("seed", gc.seed).get("threads", gc.threads);
    g.finish();
  }
  return c;
}

void PoseFreeConfig::to_json(Json& j) const {
  j["poses"] = Json{{"init", poses.init},
                    {"noise_seed", poses.noise_seed},
                    {"sigma_rot_rad", poses.sigma_rot_rad},
                    {"sigma_trans_m", poses.sigma_trans_m}};
  j["pose_optim"] = Json{{"optimize", pose_optim.optimize},
                         {"lr_rot", pose_optim.lr_rot},
                         {"lr_trans", pose_optim.lr_trans},
                         {"final_factor", pose_optim.final_factor},
                         {"identity_lr_factor", pose_optim.identity_lr_factor},
                         {"beta1", pose_optim.beta1},
                         {"beta2", pose_optim.beta2},
                         {"eps", pose_optim.eps}};
  // Written only when set, so that configs from before the key keep their hash.
  if (pose_optim.start_step != 0) j["pose_optim"]["start_step"] = pose_optim.start_step;
  j["reweight"] = Json{{"enabled", reweight.enabled},
                       {"fraction", reweight.fraction},
                       {"factor", reweight.factor},
                       {"ema", reweight.ema}};
  j["coarse_to_fine"] = coarse_to_fine;
  j["geometric"] = Json{{"enabled", geometric.enabled},
                        {"points_per_frame", geometric.points_per_frame},
                        {"edge_offsets", geometric.edge_offsets},
                        {"first_steps", geometric.first_steps},
                        {"steps_per_epoch", geometric.steps_per_epoch},
                        {"stop_progress", geometric.stop_progress},
                        {"tau_scale", geometric.tau_scale},
                        {"lr_rot", geometric.lr_rot},
                        {"lr_trans", geometric.lr_trans},
                        {"lr_final", geometric.lr_final}};
  // Written only when not GeoNLF's, so that configs from before the key keep their hash.
  if (geometric.residual != "point_to_point") j["geometric"]["residual"] = geometric.residual;
  if (geometric.seed != 1) j["geometric"]["seed"] = geometric.seed;
  if (geometric.threads != 2) j["geometric"]["threads"] = geometric.threads;
}

}  // namespace sgnlf::pipeline
