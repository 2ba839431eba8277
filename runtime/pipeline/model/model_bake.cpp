// LidarNerfModel::head_at (see model.hpp): the LiDAR head at given points and view directions,
// what a baked scene stores per vertex (runtime/bake, docs/baking.md).
#include <cmath>

#include "core/error.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

std::vector<float> LidarNerfModel::head_at(const std::vector<float>& x,
                                           const std::vector<float>& dirs, int n) {
  require(n >= 0 && x.size() == size_t(n) * 3 && dirs.size() == size_t(n) * 3,
          "LidarNerfModel::head_at: " + std::to_string(x.size()) + " and " +
              std::to_string(dirs.size()) + " floats for " + std::to_string(n) + " points");
  begin_pass();  // x_, d_, enc_, dens_, dir_enc_ and head_out_ are overwritten
  std::vector<float> out(size_t(n) * 2);
  // One point per "ray": the direction encoding's rows (max_rays_) bound the chunk.
  const int chunk = max_rays_;
  for (int b = 0; b < n; b += chunk) {
    const int m = std::min(chunk, n - b);
    x_.write(x.data() + size_t(b) * 3, size_t(m) * 3 * sizeof(float));
    d_.write(dirs.data() + size_t(b) * 3, size_t(m) * 3 * sizeof(float));
    encoder_->forward(params_, off_grid_, x_, m, enc_);
    density_.forward(params_, off_density_, enc_, m, dens_, density_ctx_);
    dirs_.forward(d_, m, dir_enc_);
    head_.forward(params_, off_head_, dens_, m, head_out_, head_ctx_, &dir_enc_, 1);
    head_out_.read(out.data() + size_t(b) * 2, size_t(m) * 2 * sizeof(float));
  }
  for (float& v : out) v = 1.0f / (1.0f + std::exp(-v));
  return out;
}

}  // namespace sgnlf::pipeline
