// The encoders' parameter backward variants (cl::EncoderBackward) side by side at their
// default sizes: serial (one work-item per level or scale-group: the CPU profile's), atomic
// (per point and level, compare-and-swap float adds) and deterministic_parallel (per point and
// level pairs, radix-sorted by entry, summed per entry in the serial order: the GPU profile's,
// bit-identical to serial). Ray-coherent points (64 samples per ray), without d_x. On a GPU
// the serial variant has only as many work-items as levels; on PoCL's CPU the cores are few and
// the serial one's cache-friendly slice walk is hard to beat, so these numbers say what the
// parallel forms cost here, not what they gain on a GPU.
#include <vector>

#include "bench_common.hpp"
#include "field/hash_grid.hpp"
#include "field/kplanes.hpp"
#include "field/time_hash_grid.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;
using bench::run_timed;
using bench::set_counters;
using bench::uniform;
using cl::EncoderBackward;

namespace {
EncoderBackward variant(const benchmark::State& state) {
  return static_cast<EncoderBackward>(state.range(1));
}
void label(benchmark::State& state) { state.SetLabel(cl::encoder_backward_name(variant(state))); }
}  // namespace

static void BM_HashGridBwdVariant(benchmark::State& state) {
  auto& rt = bench::runtime();
  field::HashGrid grid(rt, field::HashGridConfig{});
  grid.set_backward(variant(state));
  const int n = int(state.range(0));
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * grid.n_output(), -1, 1, 3));
  cl::Buffer b_g(rt, params.size() * 4);
  const double secs = run_timed(state, [&] { grid.backward(b_p, 0, b_x, n, b_d, b_g, 0); });
  set_counters(state, secs, n, 0, 0);
  label(state);
}

static void BM_TimeHashGridBwdVariant(benchmark::State& state) {
  auto& rt = bench::runtime();
  field::TimeHashGrid grid(rt, field::TimeHashGridConfig{});
  grid.set_backward(variant(state));
  const int n = int(state.range(0));
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_t = cl::Buffer::from(rt, uniform(size_t(n), 0, 1, 4));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * grid.n_output(), -1, 1, 3));
  cl::Buffer b_g(rt, params.size() * 4);
  const double secs = run_timed(state, [&] { grid.backward(b_p, 0, b_x, b_t, n, b_d, b_g, 0); });
  set_counters(state, secs, n, 0, 0);
  label(state);
}

static void BM_KPlanesBwdVariant(benchmark::State& state) {
  auto& rt = bench::runtime();
  field::KPlanes kp(rt, field::KPlanesConfig{});
  kp.set_backward(variant(state));
  const int n = int(state.range(0));
  std::vector<float> params(kp.n_params());
  kp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_t = cl::Buffer::from(rt, uniform(size_t(n), 0, 1, 4));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * kp.n_output(), -1, 1, 3));
  cl::Buffer b_g(rt, params.size() * 4);
  const double secs = run_timed(state, [&] { kp.backward(b_p, 0, b_x, b_t, n, b_d, b_g, 0); });
  set_counters(state, secs, n, 0, 0);
  label(state);
}

// Second argument: 0 serial, 1 atomic, 2 deterministic_parallel (cl::EncoderBackward).
#define VARIANTS(BM, N)                                                                      \
  BENCHMARK(BM)->Args({N, 0})->Args({N, 1})->Args({N, 2})->UseManualTime()->Unit(           \
      benchmark::kMillisecond)
VARIANTS(BM_HashGridBwdVariant, 1 << 16);
VARIANTS(BM_TimeHashGridBwdVariant, 1 << 16);
VARIANTS(BM_KPlanesBwdVariant, 1 << 16);
