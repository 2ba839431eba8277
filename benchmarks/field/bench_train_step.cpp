// One training step of the whole field at a batch of samples (method.md §0): hash grid →
// density MLP → direction encoding + head input → LiDAR head, the backward chain down to d_x
// and d_dir, and Adam over the flat buffer. Run with the deterministic and the atomic hash-grid
// backward: the difference is what determinism costs at step level.
#include "bench_common.hpp"
#include "field/adam.hpp"
#include "field/dir_encoding.hpp"
#include "field/hash_grid.hpp"
#include "field/mlp.hpp"
#include "field/param_layout.hpp"

using namespace sgnlf;
using field::Activation;

static void train_step(benchmark::State& state, bool deterministic, bool half) {
  auto& rt = bench::runtime();
  field::HashGridConfig hc;
  hc.deterministic = deterministic;
  hc.half_table = half;
  field::HashGrid grid(rt, hc);
  field::Mlp density(rt, field::make_mlp_spec(grid.n_output(), 64, 1, 16, Activation::Relu));
  field::DirEncoding dir_enc(rt);
  field::Mlp head(rt, field::make_mlp_spec(dir_enc.head_width(), 64, 3, 2, Activation::Relu));
  field::ParamLayout layout;
  const auto s_grid = layout.add("hash_grid", grid.n_params());
  const auto s_dens = layout.add("density_mlp", density.n_params());
  const auto s_head = layout.add("head_mlp", head.n_params());
  std::vector<float> host(layout.total(), 0.0f);
  grid.init_params(host, s_grid.offset, 1);
  density.init_params(host, s_dens.offset, 2);
  head.init_params(host, s_head.offset, 3);

  const int samples = 64, rays = int(state.range(0)) / samples, n = rays * samples;
  auto b_params = cl::Buffer::from(rt, host);
  cl::Buffer b_grad(rt, host.size() * 4);
  b_grad.fill_zero();
  auto b_x = cl::Buffer::from(rt, bench::uniform(size_t(n) * 3, -1, 1, 4));
  auto b_dir = cl::Buffer::from(rt, bench::uniform(size_t(rays) * 3, -0.5f, 0.5f, 5));
  auto b_dout = cl::Buffer::from(rt, bench::uniform(size_t(n) * 2, -1e-3f, 1e-3f, 6));
  auto b_ddens = cl::Buffer::from(rt, bench::uniform(size_t(n) * 16, -1e-3f, 1e-3f, 7));
  const size_t lf = size_t(grid.n_output());
  cl::Buffer b_enc(rt, n * lf * 4), b_dens(rt, size_t(n) * 64), b_denc(rt, size_t(rays) * 288),
      b_head_in(rt, size_t(n) * 87 * 4), b_out(rt, size_t(n) * 8),
      b_dhead_in(rt, size_t(n) * 87 * 4), b_dpenc(rt, n * lf * 4), b_ddenc(rt, size_t(rays) * 288),
      b_dx(rt, size_t(n) * 12), b_ddir(rt, size_t(rays) * 12);
  field::MlpContext c_dens, c_head;
  field::Adam adam(rt, layout.total());
  const double secs = bench::run_timed(state, [&] {
    grid.forward(b_params, s_grid.offset, b_x, n, b_enc);
    density.forward(b_params, s_dens.offset, b_enc, n, b_dens, c_dens);
    dir_enc.forward(b_dir, rays, b_denc);
    dir_enc.head_input_forward(b_dens, b_denc, rays, samples, b_head_in);
    head.forward(b_params, s_head.offset, b_head_in, n, b_out, c_head);
    head.backward(b_params, s_head.offset, c_head, b_out, b_dout, b_grad, s_head.offset,
                  &b_dhead_in);
    dir_enc.head_input_backward(b_dhead_in, rays, samples, b_ddens, b_ddenc);
    dir_enc.backward(b_dir, rays, b_ddenc, b_ddir);
    density.backward(b_params, s_dens.offset, c_dens, b_dens, b_ddens, b_grad, s_dens.offset,
                     &b_dpenc);
    grid.backward(b_params, s_grid.offset, b_x, n, b_dpenc, b_grad, s_grid.offset, &b_dx);
    adam.begin_step();
    adam.update(b_params, b_grad, 0, layout.total(), 1e-3f);
    grid.params_changed();
  });
  const double macs = density.spec().macs_per_point() + head.spec().macs_per_point();
  bench::set_counters(state, secs, n, double(n) * macs * 6, 0);
}
static void BM_TrainStepDeterministic(benchmark::State& s) { train_step(s, true, false); }
static void BM_TrainStepAtomic(benchmark::State& s) { train_step(s, false, false); }
static void BM_TrainStepDeterministicHalfTable(benchmark::State& s) { train_step(s, true, true); }
BENCHMARK(BM_TrainStepDeterministic)->Arg(1 << 16)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepAtomic)->Arg(1 << 16)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TrainStepDeterministicHalfTable)->Arg(1 << 16)->UseManualTime()->Unit(benchmark::kMillisecond);
