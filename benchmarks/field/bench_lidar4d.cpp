// Microbenchmarks of LiDAR4D's composite encoder (field/lidar4d_encoder.hpp, method.md §2) at
// its published sizes: forward and backward (with d_x) of the whole 4D hybrid encoding inside a
// sequence (both flowed neighbours blended) and with blending off, on ray-coherent points of
// one frame. The ratio of the two is the price of the scene-flow blending: the flow field plus
// two more passes over the dynamic planes and time hash. Reports points/s only: the parts'
// byte counts are bench_encoder4d's.
#include <vector>

#include "bench_common.hpp"
#include "field/lidar4d_encoder.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;
using bench::run_timed;
using bench::set_counters;

static void lidar4d(benchmark::State& state, bool backward) {
  auto& rt = bench::runtime();
  field::Lidar4DEncoderConfig cfg;
  cfg.blend = state.range(1) != 0;
  field::Lidar4DEncoder enc(rt, cfg);
  enc.set_frame(10, 0, 51);
  const int n = int(state.range(0)), w = enc.width();
  std::vector<float> params(enc.n_params());
  enc.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_d = cl::Buffer::from(rt, std::vector<float>(size_t(n) * size_t(w), 1e-3f));
  cl::Buffer b_enc(rt, size_t(n) * size_t(w) * 4), b_g(rt, params.size() * 4),
      b_dx(rt, size_t(n) * 12);
  enc.forward(b_p, 0, b_x, n, b_enc);
  const double secs = run_timed(state, [&] {
    if (backward)
      enc.backward(b_p, 0, b_x, n, b_d, b_g, 0, &b_dx);
    else
      enc.forward(b_p, 0, b_x, n, b_enc);
  });
  set_counters(state, secs, n, 0, 0);
}
static void BM_Lidar4DFwd(benchmark::State& s) { lidar4d(s, false); }
static void BM_Lidar4DBwd(benchmark::State& s) { lidar4d(s, true); }
BENCHMARK(BM_Lidar4DFwd)->Args({1 << 16, 1})->Args({1 << 16, 0})->UseManualTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Lidar4DBwd)->Args({1 << 16, 1})->Args({1 << 16, 0})->UseManualTime()
    ->Unit(benchmark::kMillisecond);
