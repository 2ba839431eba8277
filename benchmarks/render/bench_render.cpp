// Render microbenchmarks: ray sampling, volume rendering forward/backward, ray-gradient
// reduction and the range loss, in rays/s, samples/s and GB/s of compulsory traffic (OpenCL
// event times), against a streaming probe (saxpy, 12 bytes per element) measured first in the
// same run. Traffic per sample is stated next to each benchmark.
#include <vector>

#include "core/rng.hpp"
#include "render/range_loss.hpp"
#include "render/ray_gradient.hpp"
#include "render/ray_sampler.hpp"
#include "render/volume_renderer.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;

namespace {
const float kScale = 0.0125f;
double g_stream_gbps = 0;  // set by BM_StreamProbe

std::vector<float> random_vec(size_t n, float lo, float hi, uint64_t seed) {
  Rng rng(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = rng.uniform(lo, hi);
  return v;
}

// Rays with unit directions along a fixed pattern; origins near the centre.
void make_rays(int n, cl::Buffer& o, cl::Buffer& d) {
  auto& rt = bench::runtime();
  std::vector<float> vo = random_vec(3 * size_t(n), -0.1f, 0.1f, 1), vd(3 * size_t(n));
  for (int r = 0; r < n; ++r) {
    const float a = 0.001f * r;
    vd[3 * r] = std::cos(a) * 0.9950f, vd[3 * r + 1] = std::sin(a) * 0.9950f,
           vd[3 * r + 2] = 0.0998f;
  }
  o = cl::Buffer::from(rt, vo);
  d = cl::Buffer::from(rt, vd);
}

// Adds rays/s, samples/s, GB/s and % of the streaming probe from the summed event times.
void report(benchmark::State& state, double total_ms, size_t rays, size_t samples, double bytes) {
  const double s = total_ms * 1e-3, it = double(state.iterations());
  state.counters["Mrays_per_s"] = it * rays / s * 1e-6;
  state.counters["Msamples_per_s"] = it * samples / s * 1e-6;
  state.counters["GB_per_s"] = it * bytes / s * 1e-9;
  if (g_stream_gbps > 0)
    state.counters["pct_stream"] = 100.0 * it * bytes / s * 1e-9 / g_stream_gbps;
}

render::RenderConfig sampling_config(int samples, int importance = 0) {
  render::RenderConfig c;
  c.n_samples = samples;
  c.n_importance = importance;
  return c;
}
}  // namespace

static void BM_StreamProbe(benchmark::State& state) {
  bench::add_device_context();
  auto& rt = bench::runtime();
  const int n = 1 << 24;
  auto x = cl::Buffer::from(rt, std::vector<float>(n, 1.f)),
       y = cl::Buffer::from(rt, std::vector<float>(n, 1.f));
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 1.0f, x, y);
  k.launch({size_t(n)}).wait();
  double ms = 0;
  for (auto _ : state) {
    const double t = k.launch({size_t(n)}).elapsed_ms();
    ms += t;
    state.SetIterationTime(t * 1e-3);
  }
  g_stream_gbps = state.iterations() * 12.0 * n / (ms * 1e-3) * 1e-9;
  state.counters["GB_per_s"] = g_stream_gbps;
}
BENCHMARK(BM_StreamProbe)->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(0.5);

// Uniform jittered sampling: writes t and x (16 B/sample).
static void BM_SampleUniform(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0)), S = int(state.range(1));
  render::RaySampler sampler(rt, sampling_config(S), kScale);
  cl::Buffer o, d;
  make_rays(n_rays, o, d);
  const size_t n = size_t(n_rays) * S;
  cl::Buffer t(rt, n * 4), x(rt, n * 12);
  sampler.uniform(o, d, n_rays, true, 1, 0, t, x).wait();
  double ms = 0;
  uint32_t step = 0;
  for (auto _ : state) {
    const double e = sampler.uniform(o, d, n_rays, true, 1, ++step, t, x).elapsed_ms();
    ms += e;
    state.SetIterationTime(e * 1e-3);
  }
  report(state, ms, n_rays, n, 16.0 * n);
}
BENCHMARK(BM_SampleUniform)
    ->Args({4096, 64})
    ->Args({4096, 192})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Importance sampling: reads coarse t, w (8 B/coarse sample), writes t, x (16 B/output).
static void BM_SampleImportance(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0)), Sc = int(state.range(1)), Sf = int(state.range(2));
  render::RaySampler sampler(rt, sampling_config(Sc, Sf), kScale);
  cl::Buffer o, d;
  make_rays(n_rays, o, d);
  const size_t nc = size_t(n_rays) * Sc, no = size_t(n_rays) * (Sc + Sf);
  cl::Buffer tc(rt, nc * 4), xc(rt, nc * 12), t(rt, no * 4), x(rt, no * 12), src(rt, no * 4);
  sampler.uniform(o, d, n_rays, true, 1, 0, tc, xc).wait();
  auto w = cl::Buffer::from(rt, random_vec(nc, 0.f, 0.05f, 2));
  double ms = 0;
  uint32_t step = 0;
  for (auto _ : state) {
    const double e =
        sampler.importance(o, d, n_rays, Sc, tc, w, true, 1, ++step, t, x, src).elapsed_ms();
    ms += e;
    state.SetIterationTime(e * 1e-3);
  }
  report(state, ms, n_rays, no, 8.0 * nc + 20.0 * no);
}
BENCHMARK(BM_SampleImportance)
    ->Args({4096, 64, 32})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

struct VolumeInputs {
  cl::Buffer t, h0, head, out, w, grad_out, gh0, ghead;
};

static VolumeInputs volume_inputs(cl::Runtime& rt, int n_rays, int S) {
  const size_t n = size_t(n_rays) * S;
  std::vector<float> t(n);
  for (size_t s = 0; s < n; ++s) t[s] = (1.f + (s % S + 0.5f) * 80.f / S) * kScale;
  VolumeInputs v;
  v.t = cl::Buffer::from(rt, t);
  v.h0 = cl::Buffer::from(rt, random_vec(n, -2.f, 3.f, 3));
  v.head = cl::Buffer::from(rt, random_vec(2 * n, -3.f, 3.f, 4));
  v.out = cl::Buffer(rt, size_t(n_rays) * 12);
  v.w = cl::Buffer(rt, n * 4);
  v.grad_out = cl::Buffer::from(rt, random_vec(3 * size_t(n_rays), -1.f, 1.f, 5));
  v.gh0 = cl::Buffer(rt, n * 4);
  v.ghead = cl::Buffer(rt, n * 8);
  return v;
}

// Forward: reads t, h0, head (16 B/sample), writes weights (4 B/sample).
static void BM_VolumeForward(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0)), S = int(state.range(1));
  render::VolumeRenderer vr(rt, sampling_config(S), kScale);
  auto v = volume_inputs(rt, n_rays, S);
  vr.forward(v.t, v.h0, v.head, n_rays, S, v.out, v.w).wait();
  double ms = 0;
  for (auto _ : state) {
    const double e = vr.forward(v.t, v.h0, v.head, n_rays, S, v.out, v.w).elapsed_ms();
    ms += e;
    state.SetIterationTime(e * 1e-3);
  }
  const size_t n = size_t(n_rays) * S;
  report(state, ms, n_rays, n, 20.0 * n);
}
BENCHMARK(BM_VolumeForward)
    ->Args({4096, 64})
    ->Args({4096, 192})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Backward: reads t, h0 twice, head, weights (28 B/sample), writes grad_h0, grad_head (12 B).
static void BM_VolumeBackward(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0)), S = int(state.range(1));
  render::VolumeRenderer vr(rt, sampling_config(S), kScale);
  auto v = volume_inputs(rt, n_rays, S);
  vr.forward(v.t, v.h0, v.head, n_rays, S, v.out, v.w);
  vr.backward(v.t, v.h0, v.head, v.w, v.grad_out, n_rays, S, v.gh0, v.ghead).wait();
  double ms = 0;
  for (auto _ : state) {
    const double e =
        vr.backward(v.t, v.h0, v.head, v.w, v.grad_out, n_rays, S, v.gh0, v.ghead).elapsed_ms();
    ms += e;
    state.SetIterationTime(e * 1e-3);
  }
  const size_t n = size_t(n_rays) * S;
  report(state, ms, n_rays, n, 40.0 * n);
}
BENCHMARK(BM_VolumeBackward)
    ->Args({4096, 64})
    ->Args({4096, 192})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Median depth (evaluation diagnostic): reads t and the weights up to each ray's crossing; the
// GB/s count the whole ray (8 B/sample), an upper bound of its traffic. The eval shape: a
// 2048-ray render chunk with 128 + 32 samples.
static void BM_MedianDepth(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0)), S = int(state.range(1));
  render::VolumeRenderer vr(rt, sampling_config(S), kScale);
  auto v = volume_inputs(rt, n_rays, S);
  vr.forward(v.t, v.h0, v.head, n_rays, S, v.out, v.w);
  vr.median_depth(v.t, v.w, n_rays, S, v.out).wait();
  double ms = 0;
  for (auto _ : state) {
    const double e = vr.median_depth(v.t, v.w, n_rays, S, v.out).elapsed_ms();
    ms += e;
    state.SetIterationTime(e * 1e-3);
  }
  const size_t n = size_t(n_rays) * S;
  report(state, ms, n_rays, n, 8.0 * n);
}
BENCHMARK(BM_MedianDepth)
    ->Args({2048, 160})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Ray-gradient reduction: reads t and dL/dx (16 B/sample).
static void BM_RayGradReduce(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0)), S = int(state.range(1));
  const size_t n = size_t(n_rays) * S;
  render::RayGradReducer red(rt);
  auto t = cl::Buffer::from(rt, random_vec(n, 0.f, 1.f, 6));
  auto gx = cl::Buffer::from(rt, random_vec(3 * n, -1.f, 1.f, 7));
  cl::Buffer go(rt, size_t(n_rays) * 12), gd(rt, size_t(n_rays) * 12);
  red.reduce(t, gx, n_rays, S, go, gd).wait();
  double ms = 0;
  for (auto _ : state) {
    const double e = red.reduce(t, gx, n_rays, S, go, gd).elapsed_ms();
    ms += e;
    state.SetIterationTime(e * 1e-3);
  }
  report(state, ms, n_rays, n, 16.0 * n);
}
BENCHMARK(BM_RayGradReduce)
    ->Args({4096, 64})
    ->Args({4096, 192})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// Range loss + patch gradient loss + 4 reductions (6 launches), wall time to completion.
static void BM_RangeLoss(benchmark::State& state) {
  auto& rt = bench::runtime();
  const int n_rays = int(state.range(0));
  render::RenderConfig cfg = sampling_config(64);
  render::RangeLoss rl(rt, cfg, kScale);
  const int n_patches = n_rays / (cfg.patch_rows * cfg.patch_cols);
  std::vector<float> target = random_vec(3 * size_t(n_rays), 0.f, 1.f, 8);
  for (int r = 0; r < n_rays; ++r) target[3 * r + 2] = target[3 * r + 2] < 0.8f ? 1.f : 0.f;
  auto out = cl::Buffer::from(rt, random_vec(3 * size_t(n_rays), 0.f, 1.f, 9));
  auto tar = cl::Buffer::from(rt, target);
  cl::Buffer grad(rt, 12 * size_t(n_rays)), terms3(rt, 12 * size_t(n_rays)),
      terms(rt, 4 * size_t(n_rays)), loss(rt, 16);
  for (auto _ : state) {
    rl.range(out, tar, n_rays, grad, terms3, loss);
    rl.patch_gradient(out, tar, n_patches, grad, terms, loss).wait();
  }
  state.counters["Mrays_per_s"] =
      benchmark::Counter(double(n_rays), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RangeLoss)->Arg(4096)->UseRealTime()->Unit(benchmark::kMicrosecond);
