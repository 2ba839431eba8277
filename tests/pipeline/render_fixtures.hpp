// Test fixtures for comparing renders: worst_channel_diff, and a field that terminates rays.
//
// opaque_state: `c` trained on `scene` (seed 3, run folder under
// test::temp_dir(dir)), then every density raised (the σ logit's output bias + 4, σ × 55) so that
// rays become opaque: the trained tiny fields are translucent. Left in `model`; returns its state.
#pragma once
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "field/mlp.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/train/trainer.hpp"
#include "support/test_device.hpp"

namespace sgnlf::test {

// The largest |a − b| over the rays of one output channel (renders are n × 3: depth, return
// probability, intensity).
inline double worst_channel_diff(const std::vector<float>& a, const std::vector<float>& b,
                                 int channel) {
  double worst = 0;
  for (size_t k = 0; 3 * k + 2 < a.size(); ++k)
    worst = std::max(worst, double(std::fabs(a[3 * k + size_t(channel)] - b[3 * k + size_t(channel)])));
  return worst;
}

inline std::vector<float> opaque_state(pipeline::LidarNerfModel& model, const pipeline::Scene& scene,
                                       const pipeline::TrainConfig& c, const std::string& dir) {
  pipeline::TrainOptions opt;
  opt.run_dir = temp_dir(dir);
  opt.seed = 3;
  opt.show_progress = false;
  pipeline::train(model, scene, c, opt);
  std::vector<float> st = model.params();
  const auto& f = c.field;
  const field::Mlp dens(runtime(),
                        field::make_mlp_spec(f.grid.levels * f.grid.features, f.density_hidden, 1,
                                             1 + f.geo_features, field::Activation::Relu));
  const size_t sigma_bias = model.layout().slice("density_mlp").offset + dens.layer_offset(1) +
                            size_t(f.density_hidden) * size_t(field::Mlp::pad16(1 + f.geo_features));
  st[sigma_bias] += 4.0f;
  model.set_params(st);
  return st;
}

}  // namespace sgnlf::test
