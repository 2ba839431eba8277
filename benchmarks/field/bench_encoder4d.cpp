// Microbenchmarks of LiDAR4D's 4D encodings at their published sizes (method.md §2): the
// K-Planes planes (kernels/field/kplanes.cl) and the time-sliced 2D hash grids
// (kernels/field/hashgrid_time.cl), forward and backward, on ray-coherent points with one time
// per batch (LiDAR4D trains on one frame per step). Each reports points/s, the bytes the kernel
// touches (every corner entry read, x and t read, the encoding written) as GB/s with its
// fraction of the streaming roofline (frac_peak), and the corner-entry reads as gathers/s with
// their fraction of the probe's random-gather rate from DRAM (frac_gather_peak). Most corner
// reads hit the L2 (planes below 256² points, one time slice pair of 2^12–2^14-entry tables),
// so a fraction above 1 says the kernel is not bound by memory but by its arithmetic.
#include <vector>

#include "bench_common.hpp"
#include "field/kplanes.hpp"
#include "field/time_hash_grid.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;
using bench::run_timed;
using bench::set_counters;
using bench::uniform;
using field::PlaneGroups;

namespace {
void set_gathers(benchmark::State& state, double secs, double gathers) {
  const double g = gathers * double(state.iterations()) / std::max(secs, 1e-12);
  state.counters["gathers_per_s"] = g;
  state.counters["peak_gathers_per_s"] = bench::roofline().gathers;
  state.counters["frac_gather_peak"] = g / bench::roofline().gathers;
}
}  // namespace

// Forward: per point and scale, 3 planes × 4 corners × F floats per group.
// Second argument: points per work-item (KPlanesConfig::chunk; 0 = auto).
static void kplanes_fwd(benchmark::State& state, PlaneGroups groups) {
  auto& rt = bench::runtime();
  field::KPlanesConfig cfg;
  cfg.chunk = int(state.range(1));
  field::KPlanes kp(rt, cfg);
  const int n = int(state.range(0)), w = kp.n_output(groups);
  std::vector<float> params(kp.n_params());
  kp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_t = cl::Buffer::from(rt, std::vector<float>(size_t(n), 0.4f));
  cl::Buffer b_enc(rt, size_t(n) * w * 4);
  const double secs = run_timed(state, [&] { kp.forward(b_p, 0, b_x, b_t, n, b_enc, groups); });
  const double corners = double(w) / kp.config().features * 3 * 4;  // per point
  set_counters(state, secs, n, 0, double(n) * (corners * kp.config().features * 4 + 16 + w * 4));
  set_gathers(state, secs, double(n) * corners);
}
static void BM_KPlanesFwd(benchmark::State& s) { kplanes_fwd(s, PlaneGroups::Both); }
static void BM_KPlanesFwdDynamic(benchmark::State& s) { kplanes_fwd(s, PlaneGroups::Dynamic); }
BENCHMARK(BM_KPlanesFwd)->Args({1 << 18, 0})->Args({1 << 18, 16})->Args({1 << 18, 256})
    ->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KPlanesFwdDynamic)->Args({1 << 18, 0})->UseManualTime()->Unit(benchmark::kMillisecond);

// Backward: per point and scale-group unit the kernel reads the 3 planes' 4 corners and reads
// and writes the same 12 gradient entries (36 entry accesses); d_x comes from the same reads
// (per unit 3 floats written, then summed by the reduce); the gradient slice is zeroed once.
static void kplanes_bwd(benchmark::State& state, bool with_dx) {
  auto& rt = bench::runtime();
  field::KPlanes kp(rt, field::KPlanesConfig{});
  const int n = int(state.range(0)), w = kp.n_output();
  std::vector<float> params(kp.n_params());
  kp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_t = cl::Buffer::from(rt, std::vector<float>(size_t(n), 0.4f));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * w, -1, 1, 3));
  cl::Buffer b_g(rt, params.size() * 4), b_dx(rt, size_t(n) * 12);
  const double secs = run_timed(
      state, [&] { kp.backward(b_p, 0, b_x, b_t, n, b_d, b_g, 0, with_dx ? &b_dx : nullptr); });
  const double units = double(w) / kp.config().features;  // scale × group per point
  const double corners = units * 3 * (3 * 4);
  const double bytes = double(n) * (corners * kp.config().features * 4 + 16 + w * 4 +
                                    (with_dx ? units * 24 + 12 : 0)) +
                       double(params.size()) * 4;
  set_counters(state, secs, n, 0, bytes);
  set_gathers(state, secs, double(n) * corners);
}
static void BM_KPlanesBwd(benchmark::State& s) { kplanes_bwd(s, false); }
static void BM_KPlanesBwdWithDx(benchmark::State& s) { kplanes_bwd(s, true); }
BENCHMARK(BM_KPlanesBwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KPlanesBwdWithDx)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

// Forward: per point and level, 3 planes × 2 time slices × 4 corners × F floats; at one time
// for all points (forward_at) 3 planes × 4 corners of the blended one-slice table, after the
// blend pass over the two slices (2 reads and a write per entry).
static void time_hash_fwd(benchmark::State& state, bool at_time) {
  auto& rt = bench::runtime();
  field::TimeHashGrid grid(rt, field::TimeHashGridConfig{});
  const int n = int(state.range(0)), w = grid.n_output(), f = grid.config().features;
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_t = cl::Buffer::from(rt, std::vector<float>(size_t(n), 0.4f));
  cl::Buffer b_enc(rt, size_t(n) * w * 4);
  const double secs = run_timed(state, [&] {
    if (at_time)
      grid.forward_at(b_p, 0, b_x, 0.4f, n, b_enc);
    else
      grid.forward(b_p, 0, b_x, b_t, n, b_enc);
  });
  const double slices = at_time ? 1 : 2, corners = double(grid.config().levels) * 3 * slices * 4;
  const double blend = at_time ? double(params.size()) / grid.config().time_slices * 3 * 4 : 0;
  set_counters(state, secs, n, 0, double(n) * (corners * f * 4 + 16 + w * 4) + blend);
  set_gathers(state, secs, double(n) * corners);
}
static void BM_TimeHashGridFwd(benchmark::State& s) { time_hash_fwd(s, false); }
static void BM_TimeHashGridFwdAtTime(benchmark::State& s) { time_hash_fwd(s, true); }
BENCHMARK(BM_TimeHashGridFwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TimeHashGridFwdAtTime)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

static void time_hash_bwd(benchmark::State& state, bool with_dx, bool at_time = false) {
  auto& rt = bench::runtime();
  field::TimeHashGrid grid(rt, field::TimeHashGridConfig{});
  const int n = int(state.range(0)), w = grid.n_output(), f = grid.config().features;
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, bench::ray_points(n / 64, 64, 2));
  auto b_t = cl::Buffer::from(rt, std::vector<float>(size_t(n), 0.4f));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * w, -1, 1, 3));
  cl::Buffer b_g(rt, params.size() * 4), b_dx(rt, size_t(n) * 12);
  const double secs = run_timed(state, [&] {
    cl::Buffer* dx = with_dx ? &b_dx : nullptr;
    if (at_time)
      grid.backward_at(b_p, 0, b_x, 0.4f, n, b_d, b_g, 0, dx);
    else
      grid.backward(b_p, 0, b_x, b_t, n, b_d, b_g, 0, dx);
  });
  // Per level: 3 planes × 2 slices × 4 corners read, and as many gradient entries read and
  // written; d_x comes from the same reads (3 floats per level written, then summed). At one
  // time: one slice, plus the blend (2 reads, 1 write per one-slice entry) and the spread
  // (1 read, 2 read-modify-writes per one-slice entry).
  const double levels = grid.config().levels;
  const double corners = levels * 3 * (3 * (at_time ? 1 : 2) * 4);
  const double slice_bytes = double(params.size()) / grid.config().time_slices * 4;
  const double bytes =
      double(n) * (corners * f * 4 + 16 + w * 4 + (with_dx ? levels * 24 + 12 : 0)) +
      double(params.size()) * 4 + (at_time ? slice_bytes * (3 + 5) : 0);
  set_counters(state, secs, n, 0, bytes);
  set_gathers(state, secs, double(n) * corners);
}
static void BM_TimeHashGridBwd(benchmark::State& s) { time_hash_bwd(s, false); }
static void BM_TimeHashGridBwdWithDx(benchmark::State& s) { time_hash_bwd(s, true); }
BENCHMARK(BM_TimeHashGridBwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TimeHashGridBwdWithDx)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
static void BM_TimeHashGridBwdAtTime(benchmark::State& s) { time_hash_bwd(s, false, true); }
static void BM_TimeHashGridBwdAtTimeWithDx(benchmark::State& s) { time_hash_bwd(s, true, true); }
BENCHMARK(BM_TimeHashGridBwdAtTime)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TimeHashGridBwdAtTimeWithDx)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
