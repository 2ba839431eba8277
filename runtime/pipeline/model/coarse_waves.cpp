// CoarseWaves: launches kernels/pipeline/coarse_waves.cl.
#include "pipeline/model/coarse_waves.hpp"

#include <cstdint>
#include <vector>

#include "pipeline/model/model_detail.hpp"

namespace sgnlf::pipeline {
using namespace model_detail;

CoarseWaves::CoarseWaves(cl::Runtime& rt, int max_rays, int n_samples, int waves, int width,
                         float eps)
    : S_(n_samples),
      waves_(waves),
      width_(width),
      eps_(eps),
      fill_(rt.kernel("pipeline/coarse_waves.cl", "pipeline_fill")),
      wave_gather_(rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_gather")),
      wave_scatter_(rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_scatter")),
      wave_done_(rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_done")) {
  const size_t R = size_t(max_rays), S = size_t(n_samples);
  const size_t wmax = (S + size_t(waves) - 1) / size_t(waves);  // the widest wave
  alive_ = floats(rt, R), done_ = floats(rt, R);
  x_w_ = floats(rt, R * wmax * 3), enc_w_ = floats(rt, R * wmax * size_t(width));
}

long CoarseWaves::run(int n_rays, const cl::Buffer& x_c, const cl::Buffer& w_c,
                      cl::Buffer& enc_c, cl::Buffer& h0, const Field& field,
                      const std::function<void()>& weights) {
  const int S = S_, n_c = n_rays * S, lf = width_;
  fill_.set_args(n_c, kDeadLogit, h0);
  fill_.launch({cl::round_up(size_t(n_c), 64)}, {64});
  std::vector<int32_t> alive(static_cast<size_t>(n_rays));
  for (int r = 0; r < n_rays; ++r) alive[size_t(r)] = r;
  long evaluated = 0;
  for (int k = 0; k < waves_ && !alive.empty(); ++k) {
    // Wave k: coarse samples [s0, s1) of the rays still alive (an even split of S).
    const int s0 = int(long(S) * k / waves_), s1 = int(long(S) * (k + 1) / waves_);
    const int width = s1 - s0, n_alive = int(alive.size()), rows = n_alive * width;
    alive_.write(alive.data(), alive.size() * sizeof(int32_t));
    const size_t global = cl::round_up(size_t(rows), 64);
    wave_gather_.set_args(n_alive, S, s0, width, alive_, x_c, x_w_);
    wave_gather_.launch({global}, {64});
    const cl::Buffer& dens = field(x_w_, rows, enc_w_);
    wave_scatter_.set_args(n_alive, S, s0, width, lf, kDensStride, alive_, enc_w_, dens, enc_c,
                           h0);
    wave_scatter_.launch({global}, {64});
    evaluated += rows;
    weights();
    if (k + 1 == waves_) break;
    // One host sync per wave: which rays go on (their termination index is not below s1).
    wave_done_.set_args(n_rays, S, s1, eps_, w_c, done_);
    wave_done_.launch({cl::round_up(size_t(n_rays), 64)}, {64});
    const std::vector<int32_t> done = done_.read_vec<int32_t>(size_t(n_rays));
    std::vector<int32_t> next;
    next.reserve(alive.size());
    for (int32_t r : alive)
      if (!done[size_t(r)]) next.push_back(r);
    alive.swap(next);
  }
  return evaluated;
}

}  // namespace sgnlf::pipeline
