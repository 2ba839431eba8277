// LidarNerfModel: the fast renderer (render_rays_fast, see model.hpp) and the density probe its
// occupancy grid is built from.
#include "core/config.hpp"
#include "core/error.hpp"
#include "pipeline/model/model.hpp"
#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

int LidarNerfModel::sample_capacity() const {
  return max_rays_ * (cfg_.render.n_samples + cfg_.render.n_importance);
}

std::vector<float> LidarNerfModel::density_logits(const std::vector<float>& x, int n) {
  require(n >= 0 && x.size() == size_t(n) * 3,
          "LidarNerfModel::density_logits: " + std::to_string(x.size()) + " floats for " +
              std::to_string(n) + " points");
  begin_pass();  // x_, enc_ and dens_ are overwritten: an earlier pass's activations are gone
  std::vector<float> out(static_cast<size_t>(n));
  const int chunk = sample_capacity();
  for (int b = 0; b < n; b += chunk) {
    const int m = std::min(chunk, n - b);
    x_.write(x.data() + size_t(b) * 3, size_t(m) * 3 * sizeof(float));
    encoder_->forward(params_, off_grid_, x_, m, enc_);
    density_.forward(params_, off_density_, enc_, m, dens_, density_ctx_);
    col_get_.set_args(m, kDensStride, 0, dens_, h0_);
    col_get_.launch({cl::round_up(size_t(m), 64)}, {64});
    h0_.read(out.data() + size_t(b), size_t(m) * sizeof(float));
  }
  return out;
}

std::vector<float> LidarNerfModel::render_rays_fast(const std::vector<float>& origins,
                                                    const std::vector<float>& directions, int n,
                                                    const render::OccupancyGrid& grid,
                                                    const render::FastRenderConfig& cfg) {
  require(n > 0 && n <= max_rays_, "LidarNerfModel::render_rays_fast: " + std::to_string(n) +
                                       " rays, capacity " + std::to_string(max_rays_));
  const int S = cfg_.render.n_samples, I = cfg_.render.n_importance, M = S + I;
  const bool march = cfg.layout == "march";
  if ((march ? !march_ : !fast_) || fast_cfg_.to_json() != cfg.to_json()) {
    fast_.reset(), march_.reset();
    if (march)
      march_ = std::make_unique<GridMarch>(rt_, max_rays_, M, cfg);
    else
      fast_ = std::make_unique<FastMarch>(rt_, max_rays_, M, cfg);
    fast_cfg_ = cfg;
  }
  begin_pass();  // every sample buffer is overwritten
  o_.write_vec(origins);
  d_.write_vec(directions);
  const auto density = [&](const cl::Buffer& x, int rows) -> const cl::Buffer& {
    encoder_->forward(params_, off_grid_, x, rows, enc_);
    density_.forward(params_, off_density_, enc_, rows, dens_, density_ctx_);
    return dens_;
  };
  if (march) {
    dirs_.forward(d_, n, dir_enc_);
    const auto head = [&](const cl::Buffer& dens, int rows,
                          const field::GroupIndex& index) -> const cl::Buffer& {
      head_.forward(params_, off_head_, dens, rows, g_head_, head_ctx_, &dir_enc_, 1, &index);
      return g_head_;
    };
    GridMarch::Lattice L;
    L.near = cfg_.render.near_m * scene_scale_;
    L.bin = bin_width();
    L.bound = kSceneBound;
    L.samples = S;
    L.refine = cfg.refine;
    L.coarse = cfg.coarse;
    // "mix" needs the frame's depth variance, which the fast paths do not keep: the median
    // stands for it (FastRenderer says so when it is made).
    march_->render(n, o_, d_, L, grid, cfg_.render.eval_depth != "expected", density, head, out_);
    fast_evaluated_ = march_->evaluated();
    fast_head_ = march_->head_rows();
    march_rows_ = march_->rows();
    return out_.read_vec<float>(size_t(n) * 3);
  }
  const auto clamp = [&](cl::Buffer& x, int rows) {
    clamp_.set_args(rows * 3, kSceneBound, x);
    clamp_.launch({cl::round_up(size_t(rows) * 3, 64)}, {64});
  };
  fast_evaluated_ = 0;
  march_rows_ = GridMarch::Rows{};
  if (I == 0) {
    sampler_.uniform(o_, d_, n, false, 0, 0, t_, x_);
    clamp(x_, n * S);
  } else {
    // The coarse pass marches first; its weights (dead samples at zero) give the importance
    // samples, as the protocol's coarse pass does.
    sampler_.uniform(o_, d_, n, false, 0, 0, t_c_, x_c_);
    clamp(x_c_, n * S);
    fast_evaluated_ += fast_->density_pass(n, S, x_c_, grid, h0_, head_out_, w_c_, density,
                                           [&] { renderer_.weights(t_c_, h0_, n, S, w_c_); });
    sampler_.importance(o_, d_, n, S, t_c_, w_c_, false, 0, 0, t_, x_, reuse_->sources());
    clamp(x_, n * M);
  }
  const auto merged_weights = [&] { renderer_.weights(t_, h0_, n, M, weights_); };
  if (I == 0)
    fast_evaluated_ += fast_->density_pass(n, M, x_, grid, h0_, head_out_, weights_, density,
                                           merged_weights);
  else
    fast_evaluated_ += fast_->merged_pass(n, S, M, x_, reuse_->sources(), grid, h0_, head_out_,
                                          weights_, density, merged_weights);
  dirs_.forward(d_, n, dir_enc_);
  // The head's output rows go to g_head_ (a backward buffer, unused when rendering).
  const auto head = [&](const cl::Buffer& dens, int rows,
                        const field::GroupIndex& index) -> const cl::Buffer& {
    head_.forward(params_, off_head_, dens, rows, g_head_, head_ctx_, &dir_enc_, 1, &index);
    return g_head_;
  };
  fast_head_ = fast_->head_pass(n, M, weights_, head_out_, head);
  renderer_.forward(t_, h0_, head_out_, n, M, out_, weights_);
  if (cfg_.render.eval_depth != "expected") renderer_.median_depth(t_, weights_, n, M, out_);
  return out_.read_vec<float>(size_t(n) * 3);
}

}  // namespace sgnlf::pipeline
