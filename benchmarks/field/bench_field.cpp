// Microbenchmarks of the field kernels (hash grid, MLPs, direction encoding, Adam) at training
// batch sizes. Each reports points/s and GFLOP/s or GB/s with its fraction of the roofline
// measured by the probe kernels in the same run (counters peak_gflops / peak_gbs).
// Time per iteration = enqueue of the whole pass + clFinish (includes launch overheads).
#include <vector>

#include "core/rng.hpp"
#include "field/adam.hpp"
#include "field/dir_encoding.hpp"
#include "field/hash_grid.hpp"
#include "field/mlp.hpp"
#include "bench_common.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;
using bench::run_timed;
using bench::set_counters;
using bench::uniform;
using field::Activation;

// Gather model of the hash-grid kernels: 4 random reads per point on every level whose table is
// larger than 1 MiB (the coarse levels stay in the 2 MiB L2 of this CPU and cost little); the 8
// corners form 4 x-pairs whose two entries are adjacent (dense index gx + ..., hash gx ^ ...), so
// a pair costs one cache-missing read. Reported as gathers/s beside the probe's random-gather
// rate measured in this run (peak_gathers_per_s, kernels/roofline/roofline.cl).
static void set_gather_counters(benchmark::State& state, const field::HashGrid& grid,
                                int features, double secs, double points) {
  int big = 0;
  for (const auto& lv : grid.levels())
    if (double(lv.size) * features * 4 > 1024.0 * 1024.0) ++big;
  const double g = points * 4 * big * double(state.iterations()) / std::max(secs, 1e-12);
  const double peak = bench::roofline().gathers;
  state.counters["gathers_per_s"] = g;
  state.counters["peak_gathers_per_s"] = peak;
  state.counters["frac_gather_peak"] = g / peak;
}

static void hash_fwd(benchmark::State& state, bool half, bool rays = false,
                     const char* schedule = "auto") {
  auto& rt = bench::runtime();
  field::HashGridConfig cfg;
  cfg.half_table = half;
  cfg.schedule = schedule;
  field::HashGrid grid(rt, cfg);
  const int n = int(state.range(0));
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, rays ? bench::ray_points(n / 64, 64, 2)
                                       : uniform(size_t(n) * 3, -1, 1, 2));
  cl::Buffer b_enc(rt, size_t(n) * grid.n_output() * 4);
  const double secs = run_timed(state, [&] { grid.forward(b_p, 0, b_x, n, b_enc); });
  // Bytes: 8 corner gathers of F values per level, x read, encoding written.
  const double bytes = double(n) * (16 * 8 * 2 * (half ? 2 : 4) + 12 + grid.n_output() * 4);
  set_counters(state, secs, n, 0, bytes);
  set_gather_counters(state, grid, cfg.features, secs, n);
}
static void BM_HashGridFwd(benchmark::State& s) { hash_fwd(s, false); }
static void BM_HashGridFwdHalfTable(benchmark::State& s) { hash_fwd(s, true); }
// Ray-coherent points (64 samples per ray) instead of uniform random ones.
static void BM_HashGridFwdRays(benchmark::State& s) { hash_fwd(s, false, true); }
static void BM_HashGridFwdRaysHalfTable(benchmark::State& s) { hash_fwd(s, true, true); }
static void BM_HashGridFwdRaysPerPoint(benchmark::State& s) { hash_fwd(s, false, true, "per_point"); }
static void BM_HashGridFwdRaysHalfPerPoint(benchmark::State& s) { hash_fwd(s, true, true, "per_point"); }
BENCHMARK(BM_HashGridFwdRaysPerPoint)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridFwdRaysHalfPerPoint)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridFwdRays)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridFwdRaysHalfTable)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridFwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridFwdHalfTable)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

// fp16 table refresh after an optimiser step (half_table): 16.8M parameters.
static void BM_HashGridHalfRefresh(benchmark::State& state) {
  auto& rt = bench::runtime();
  field::HashGridConfig cfg;
  cfg.half_table = true;
  field::HashGrid grid(rt, cfg);
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, uniform(3, -1, 1, 2));
  cl::Buffer b_enc(rt, size_t(grid.n_output()) * 4);
  const double secs = run_timed(state, [&] {
    grid.params_changed();
    grid.forward(b_p, 0, b_x, 1, b_enc);  // one point: the time is the refresh
  });
  set_counters(state, secs, double(params.size()), 0, double(params.size()) * 6);
}
BENCHMARK(BM_HashGridHalfRefresh)->UseManualTime()->Unit(benchmark::kMillisecond);

static void hash_bwd(benchmark::State& state, bool deterministic, bool with_dx, bool rays = false) {
  auto& rt = bench::runtime();
  field::HashGridConfig cfg;
  cfg.deterministic = deterministic;
  field::HashGrid grid(rt, cfg);
  const int n = int(state.range(0));
  std::vector<float> params(grid.n_params());
  grid.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, rays ? bench::ray_points(n / 64, 64, 2)
                                       : uniform(size_t(n) * 3, -1, 1, 2));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * grid.n_output(), -1, 1, 3));
  cl::Buffer b_g(rt, params.size() * 4), b_dx(rt, size_t(n) * 12);
  const double secs = run_timed(
      state, [&] { grid.backward(b_p, 0, b_x, n, b_d, b_g, 0, with_dx ? &b_dx : nullptr); });
  const double bytes = double(n) * (16 * 8 * 2 * 4 * (with_dx ? 3 : 2)) + double(params.size()) * 4;
  set_counters(state, secs, n, 0, bytes);
  set_gather_counters(state, grid, cfg.features, secs, double(n) * (with_dx ? 2 : 1));
}
static void BM_HashGridBwdDeterministic(benchmark::State& s) { hash_bwd(s, true, false); }
static void BM_HashGridBwdAtomic(benchmark::State& s) { hash_bwd(s, false, false); }
static void BM_HashGridBwdDeterministicWithDx(benchmark::State& s) { hash_bwd(s, true, true); }
BENCHMARK(BM_HashGridBwdDeterministic)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridBwdAtomic)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
static void BM_HashGridBwdRaysDeterministic(benchmark::State& s) { hash_bwd(s, true, false, true); }
static void BM_HashGridBwdRaysAtomic(benchmark::State& s) { hash_bwd(s, false, false, true); }
BENCHMARK(BM_HashGridBwdRaysDeterministic)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridBwdRaysAtomic)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HashGridBwdDeterministicWithDx)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

static void mlp_bench(benchmark::State& state, const field::MlpSpec& spec, bool backward) {
  auto& rt = bench::runtime();
  field::Mlp mlp(rt, spec);
  const int n = int(state.range(0));
  std::vector<float> params(mlp.n_params());
  mlp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_in = cl::Buffer::from(rt, uniform(size_t(n) * spec.n_in, -1, 1, 2));
  auto b_dout = cl::Buffer::from(rt, uniform(size_t(n) * spec.n_out(), -1, 1, 3));
  cl::Buffer b_out(rt, size_t(n) * spec.n_out() * 4), b_g(rt, params.size() * 4),
      b_din(rt, size_t(n) * spec.n_in * 4);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_in, n, b_out, ctx);
  const double secs =
      backward ? run_timed(state, [&] { mlp.backward(b_p, 0, ctx, b_out, b_dout, b_g, 0, &b_din); })
               : run_timed(state, [&] { mlp.forward(b_p, 0, b_in, n, b_out, ctx); });
  // Useful FLOPs (unpadded): forward 2·MACs, backward 4·MACs (weights + inputs).
  set_counters(state, secs, n, double(n) * spec.macs_per_point() * (backward ? 4 : 2), 0);
}
static field::MlpSpec density_spec() { return field::make_mlp_spec(32, 64, 1, 16, Activation::Relu); }
static field::MlpSpec head_spec() { return field::make_mlp_spec(87, 64, 3, 2, Activation::Relu); }
static void BM_MlpDensityFwd(benchmark::State& s) { mlp_bench(s, density_spec(), false); }
static void BM_MlpDensityBwd(benchmark::State& s) { mlp_bench(s, density_spec(), true); }
static void BM_MlpHeadFwd(benchmark::State& s) { mlp_bench(s, head_spec(), false); }
static void BM_MlpHeadBwd(benchmark::State& s) { mlp_bench(s, head_spec(), true); }
BENCHMARK(BM_MlpDensityFwd)->Arg(1 << 16)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpDensityBwd)->Arg(1 << 16)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpHeadFwd)->Arg(1 << 16)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpHeadBwd)->Arg(1 << 16)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

// The two GEMM variants of the device profiles on the same shapes (cl::GemmVariant, set over the
// Runtime's profile while the Mlp is made): args {points, 0 = cpu_tiles (kernels/field/mlp.cl,
// the "cpu" profile's), 1 = local_tiles (kernels/field/mlp_tiles.cl, the "gpu" profile's)}.
// The plain BM_Mlp* cases run whichever the device's profile chooses.
static void mlp_gemm_bench(benchmark::State& state, const field::MlpSpec& spec, bool backward) {
  auto& rt = bench::runtime();
  const cl::DeviceProfile saved = rt.device_profile();
  cl::DeviceProfile p = saved;
  p.gemm = state.range(1) == 0 ? cl::GemmVariant::CpuTiles : cl::GemmVariant::LocalTiles;
  rt.set_device_profile(p);
  field::Mlp mlp(rt, spec);  // reads the profile here
  rt.set_device_profile(saved);
  state.SetLabel(cl::gemm_name(p.gemm));
  const int n = int(state.range(0));
  std::vector<float> params(mlp.n_params());
  mlp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_in = cl::Buffer::from(rt, uniform(size_t(n) * spec.n_in, -1, 1, 2));
  auto b_dout = cl::Buffer::from(rt, uniform(size_t(n) * spec.n_out(), -1, 1, 3));
  cl::Buffer b_out(rt, size_t(n) * spec.n_out() * 4), b_g(rt, params.size() * 4),
      b_din(rt, size_t(n) * spec.n_in * 4);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_in, n, b_out, ctx);
  const double secs =
      backward ? run_timed(state, [&] { mlp.backward(b_p, 0, ctx, b_out, b_dout, b_g, 0, &b_din); })
               : run_timed(state, [&] { mlp.forward(b_p, 0, b_in, n, b_out, ctx); });
  set_counters(state, secs, n, double(n) * spec.macs_per_point() * (backward ? 4 : 2), 0);
}
static void BM_MlpGemmDensityFwd(benchmark::State& s) { mlp_gemm_bench(s, density_spec(), false); }
static void BM_MlpGemmDensityBwd(benchmark::State& s) { mlp_gemm_bench(s, density_spec(), true); }
static void BM_MlpGemmHeadFwd(benchmark::State& s) { mlp_gemm_bench(s, head_spec(), false); }
static void BM_MlpGemmHeadBwd(benchmark::State& s) { mlp_gemm_bench(s, head_spec(), true); }
BENCHMARK(BM_MlpGemmDensityFwd)->Args({1 << 18, 0})->Args({1 << 18, 1})->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpGemmDensityBwd)->Args({1 << 18, 0})->Args({1 << 18, 1})->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpGemmHeadFwd)->Args({1 << 18, 0})->Args({1 << 18, 1})->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpGemmHeadBwd)->Args({1 << 18, 0})->Args({1 << 18, 1})->UseManualTime()->Unit(benchmark::kMillisecond);

// The head as the model runs it: 15 geometric features read in place from the density output
// (stride 16) and the 72-dim direction encoding as a grouped input, one group per ray of 64
// samples. Same function as BM_MlpHead*; compare points/s. FLOPs counted as performed.
// towers = 2: LiDAR4D's separate intensity and ray-drop heads (two towers of 64, one 128-wide
// MLP with block-diagonal weights; the backward adds the off-tower gradient mask).
static void mlp_grouped_head_bench(benchmark::State& state, bool backward, int towers = 1) {
  auto& rt = bench::runtime();
  field::MlpSpec spec = field::make_mlp_spec(15, 64 * towers, 3, 2, Activation::Relu);
  spec.towers = towers;
  spec.n_in_group = 72;
  spec.in_stride = 16;
  spec.in_offset = 1;
  field::Mlp mlp(rt, spec);
  const int n = int(state.range(0)), group = 64, groups = n / group;
  std::vector<float> params(mlp.n_params());
  mlp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_in = cl::Buffer::from(rt, uniform(size_t(n) * 16, -1, 1, 2));
  auto b_y = cl::Buffer::from(rt, uniform(size_t(groups) * 72, -1, 1, 4));
  auto b_dout = cl::Buffer::from(rt, uniform(size_t(n) * 2, -1, 1, 3));
  cl::Buffer b_out(rt, size_t(n) * 2 * 4), b_g(rt, params.size() * 4),
      b_din(rt, size_t(n) * 16 * 4), b_dy(rt, size_t(groups) * 72 * 4);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_in, n, b_out, ctx, &b_y, group);
  const double secs =
      backward ? run_timed(state, [&] { mlp.backward(b_p, 0, ctx, b_out, b_dout, b_g, 0, &b_din, &b_dy); })
               : run_timed(state, [&] { mlp.forward(b_p, 0, b_in, n, b_out, ctx, &b_y, group); });
  const double macs = double(n) * spec.macs_per_point() + double(groups) * spec.macs_per_group();
  set_counters(state, secs, n, macs * (backward ? 4 : 2), 0);
}
static void BM_MlpHeadGroupedFwd(benchmark::State& s) { mlp_grouped_head_bench(s, false); }
static void BM_MlpHeadGroupedBwd(benchmark::State& s) { mlp_grouped_head_bench(s, true); }
BENCHMARK(BM_MlpHeadGroupedFwd)->Arg(1 << 16)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpHeadGroupedBwd)->Arg(1 << 16)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
static void BM_MlpHeadTowersFwd(benchmark::State& s) { mlp_grouped_head_bench(s, false, 2); }
static void BM_MlpHeadTowersBwd(benchmark::State& s) { mlp_grouped_head_bench(s, true, 2); }
BENCHMARK(BM_MlpHeadTowersFwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MlpHeadTowersBwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

// The shape of the prototype figure in performance.md: 32→64→64→16, forward + backward.
static void BM_MlpProtoFwdBwd(benchmark::State& state) {
  auto& rt = bench::runtime();
  const auto spec = field::make_mlp_spec(32, 64, 2, 16, Activation::Relu);
  field::Mlp mlp(rt, spec);
  const int n = int(state.range(0));
  std::vector<float> params(mlp.n_params());
  mlp.init_params(params, 0, 1);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_in = cl::Buffer::from(rt, uniform(size_t(n) * 32, -1, 1, 2));
  auto b_dout = cl::Buffer::from(rt, uniform(size_t(n) * 16, -1, 1, 3));
  cl::Buffer b_out(rt, size_t(n) * 64), b_g(rt, params.size() * 4), b_din(rt, size_t(n) * 128);
  field::MlpContext ctx;
  const double secs = run_timed(state, [&] {
    mlp.forward(b_p, 0, b_in, n, b_out, ctx);
    mlp.backward(b_p, 0, ctx, b_out, b_dout, b_g, 0, &b_din);
  });
  set_counters(state, secs, n, double(n) * spec.macs_per_point() * 6, 0);
}
BENCHMARK(BM_MlpProtoFwdBwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

static void BM_DirEncodingAndHeadInput(benchmark::State& state) {
  auto& rt = bench::runtime();
  field::DirEncoding de(rt);
  const int rays = 2048, samples = int(state.range(0)) / rays, n = rays * samples;
  auto b_dir = cl::Buffer::from(rt, uniform(size_t(rays) * 3, -0.5f, 0.5f, 1));
  auto b_dens = cl::Buffer::from(rt, uniform(size_t(n) * 16, -1, 1, 2));
  cl::Buffer b_enc(rt, size_t(rays) * 72 * 4), b_head(rt, size_t(n) * 87 * 4);
  const double secs = run_timed(state, [&] {
    de.forward(b_dir, rays, b_enc);
    de.head_input_forward(b_dens, b_enc, rays, samples, b_head);
  });
  set_counters(state, secs, n, 0, double(n) * (64 + 87 * 4));
}
BENCHMARK(BM_DirEncodingAndHeadInput)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

static void BM_HeadInputBwd(benchmark::State& state) {
  auto& rt = bench::runtime();
  field::DirEncoding de(rt);
  const int rays = 2048, samples = int(state.range(0)) / rays, n = rays * samples;
  auto b_dir = cl::Buffer::from(rt, uniform(size_t(rays) * 3, -0.5f, 0.5f, 1));
  auto b_dh = cl::Buffer::from(rt, uniform(size_t(n) * 87, -1, 1, 2));
  cl::Buffer b_ddens(rt, size_t(n) * 64), b_denc(rt, size_t(rays) * 72 * 4), b_ddir(rt, size_t(rays) * 12);
  const double secs = run_timed(state, [&] {
    de.head_input_backward(b_dh, rays, samples, b_ddens, b_denc);
    de.backward(b_dir, rays, b_denc, b_ddir);
  });
  set_counters(state, secs, n, 0, double(n) * (87 * 4 + 60));
}
BENCHMARK(BM_HeadInputBwd)->Arg(1 << 18)->UseManualTime()->Unit(benchmark::kMillisecond);

static void BM_Adam(benchmark::State& state) {
  auto& rt = bench::runtime();
  const size_t n = size_t(state.range(0));
  field::Adam adam(rt, n);
  auto b_p = cl::Buffer::from(rt, uniform(n, -1, 1, 1)), b_g = cl::Buffer::from(rt, uniform(n, -1, 1, 2));
  const double secs = run_timed(state, [&] {
    adam.begin_step();
    adam.update(b_p, b_g, 0, n, 1e-3f);
  });
  set_counters(state, secs, double(n), 0, double(n) * 28);  // read p, g, m, v; write p, m, v
}
BENCHMARK(BM_Adam)->Arg(16 << 20)->UseManualTime()->Unit(benchmark::kMillisecond);
