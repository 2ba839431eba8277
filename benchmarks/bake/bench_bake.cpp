// The baked scene's ray caster (kernels/bake/raycast.cl, docs/baking.md) in rays/s and frames/s
// (OpenCL event times) on an analytic street baked as `sgnlf bake` bakes a field: a ground at
// z = 0, facades at y = ±8 m over 120 m, 0.1 m voxels in bricks of 8, the field's σ rising over
// ~0.1 m behind each surface. Spinning sensors at the street's centre, 1.7 m up, 360° × [−25°, 3°]:
// 32 × 1080, 64 × 2048, 128 × 2048, and the twins' 66 × 1030. GB/s counts the compulsory
// traffic only (ray in 24 B, out 32 B): the gathers inside bricks stay in cache and are not
// counted, so frac_peak_bw is a lower bound.
#include <algorithm>
#include <cmath>
#include <vector>

#include "bake/bake.hpp"
#include "bake/ray_caster.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;

namespace {

float street_sdf(float x, float y, float z) {
  (void)x;
  return std::min(z, 8.0f - std::fabs(y));
}

const bake::BakedScene& street() {
  static const bake::BakedScene s = [] {
    bake::BakeInput in;
    for (float x = -60.0f; x <= 60.0f; x += 0.2f) {
      for (float y = -8.0f; y <= 8.0f; y += 0.2f) in.returns_m.insert(in.returns_m.end(), {x, y, 0.0f});
      for (float z = 0.0f; z <= 10.0f; z += 0.2f) {
        in.returns_m.insert(in.returns_m.end(), {x, 8.0f, z});
        in.returns_m.insert(in.returns_m.end(), {x, -8.0f, z});
      }
    }
    in.origins_m = {0.0f, 0.0f, 1.7f};
    in.near_m = 1.0f, in.far_m = 81.0f;
    bake::FieldProbe p;
    p.density = [](const std::vector<float>& x, int n) {
      std::vector<float> l(static_cast<size_t>(n));
      for (int i = 0; i < n; ++i)
        l[size_t(i)] = std::clamp(
            3.0f - 40.0f * street_sdf(x[3 * size_t(i)], x[3 * size_t(i) + 1], x[3 * size_t(i) + 2]),
            -12.0f, 10.0f);
      return l;
    };
    p.head = [](const std::vector<float>&, const std::vector<float>&, int n) {
      return std::vector<float>(static_cast<size_t>(n) * 2, 0.7f);
    };
    return bake::bake_field(bake::BakeConfig{}, in, p);
  }();
  return s;
}

void bm_raycast(benchmark::State& state) {
  bench::add_device_context();
  auto& rt = bench::runtime();
  const int H = int(state.range(0)), W = int(state.range(1));
  const size_t n = size_t(H) * size_t(W);
  std::vector<float> o(n * 3), d(n * 3);
  const float pi = 3.14159265f;
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c) {
      const float el = (3.0f - 28.0f * float(r) / float(H - 1)) * pi / 180.0f,
                  az = 2.0f * pi * float(c) / float(W);
      const size_t p = size_t(r) * size_t(W) + size_t(c);
      o[3 * p] = 0.0f, o[3 * p + 1] = 0.0f, o[3 * p + 2] = 1.7f;
      d[3 * p] = std::cos(el) * std::cos(az), d[3 * p + 1] = std::cos(el) * std::sin(az);
      d[3 * p + 2] = std::sin(el);
    }
  bake::RayCaster caster(rt, street());
  const size_t out_bytes = bake::RayCaster::kOutputs * sizeof(float);
  cl::Buffer bo = cl::Buffer::from(rt, o), bd = cl::Buffer::from(rt, d), out(rt, n * out_bytes);
  caster.cast(bo, bd, int(n), out).wait();  // build and warm
  double total_ms = 0.0;
  for (auto _ : state) {
    const cl::Event e = caster.cast(bo, bd, int(n), out);
    e.wait();
    const double ms = e.elapsed_ms();
    total_ms += ms;
    state.SetIterationTime(ms * 1e-3);
  }
  const double s = total_ms * 1e-3, it = double(state.iterations());
  state.counters["Mrays_per_s"] = it * double(n) / s * 1e-6;
  state.counters["frames_per_s"] = it / s;
  state.counters["scene_MiB"] = double(street().bytes()) / double(1 << 20);
  bench::set_roofline_counters(state, s, 0.0, it * double(n) * (24.0 + double(out_bytes)));
}

}  // namespace

BENCHMARK(bm_raycast)->Name("BM_BakedRaycast")->Args({32, 1080})->Args({66, 1030})->Args({64, 2048})
    ->Args({128, 2048})->UseManualTime()->Unit(benchmark::kMillisecond);
