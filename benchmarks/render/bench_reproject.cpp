// Cross-frame reprojection (method.md §4.3) at the quick presets' range-image sizes: two
// consecutive simulated frames (kitti360-low-a 66 × 1030, nuscenes-low-a 32 × 1080; the quick
// presets train on the sensors' full images), frame j's pose 0.3 m and 2° off its true value.
// Wall time per call as the training loop pays it (forward: four enqueued kernels and a
// finish; backward: two kernels, the read of the per-group partials and the host sum), and
// the device time per kernel from the runtime's profile (events, queue serialised).
#include <map>
#include <string>

#include "datasets/simulate.hpp"
#include "render/cross_frame_reprojection.hpp"
#include "support/bench_support.hpp"

using namespace sgnlf;

namespace {
const char* kSequences[] = {"kitti360-low-a", "nuscenes-low-a"};

struct PairInputs {
  Sensor sensor;
  std::vector<float> depth_i, grad_range;
  Pose T_world_lidar_i, T_world_lidar_j;
};

const PairInputs& inputs(int which) {
  static std::map<int, PairInputs> cache;
  auto it = cache.find(which);
  if (it != cache.end()) return it->second;
  SimOptions o;
  o.sequence = kSequences[which];
  o.frames = 2;
  o.threads = 1;
  const Dataset d = simulate_dataset(o);
  PairInputs p;
  p.sensor = d.sensor;
  p.depth_i = d.frames[0].image.range;
  p.T_world_lidar_i = d.frames[0].T_world_lidar;
  Pose off = Pose::Identity();
  off.linear() = exp_so3(Vec3(0.01, -0.02, 0.03));
  off.translation() = Vec3(0.2, -0.1, 0.15);
  p.T_world_lidar_j = d.frames[1].T_world_lidar * off;
  p.grad_range.resize(size_t(d.sensor.height) * d.sensor.width);
  for (size_t t = 0; t < p.grad_range.size(); ++t) p.grad_range[t] = float(int(t % 7) - 3) * 1e-3f;
  return cache.emplace(which, std::move(p)).first->second;
}

struct Bench {
  const PairInputs& in;
  render::CrossFrameReprojection rp;
  cl::Buffer depth, grad_range, grad_depth;
  render::ReprojectionOutput out;
  explicit Bench(int which)
      : in(inputs(which)),
        rp(bench::runtime(), in.sensor, in.sensor, 1.0),
        depth(cl::Buffer::from(bench::runtime(), in.depth_i)),
        grad_range(cl::Buffer::from(bench::runtime(), in.grad_range)),
        grad_depth(bench::runtime(), in.depth_i.size() * 4),
        out(rp.make_output()) {}
  render::ReprojectionContext forward() {
    return rp.forward(depth, in.T_world_lidar_i, in.T_world_lidar_j, out);
  }
  void backward(const render::ReprojectionContext& ctx) {
    benchmark::DoNotOptimize(rp.backward(ctx, depth, out, grad_range, grad_depth, Vec6::Zero(), Vec6::Zero()));
  }
  void label(benchmark::State& state) {
    state.SetLabel(std::string(kSequences[state.range(0)]) + " " + std::to_string(in.sensor.height) +
                   "x" + std::to_string(in.sensor.width));
    state.counters["Mpixels_per_s"] = benchmark::Counter(
        double(rp.source_pixels()) * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
  }
};
}  // namespace

static void BM_ReprojectForward(benchmark::State& state) {
  bench::add_device_context();
  Bench b(int(state.range(0)));
  b.forward();
  bench::runtime().finish();
  for (auto _ : state) {
    b.forward();
    bench::runtime().finish();
  }
  b.label(state);
}
BENCHMARK(BM_ReprojectForward)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_ReprojectBackward(benchmark::State& state) {
  Bench b(int(state.range(0)));
  const auto ctx = b.forward();
  b.backward(ctx);
  for (auto _ : state) b.backward(ctx);
  b.label(state);
}
BENCHMARK(BM_ReprojectBackward)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_ReprojectForwardBackward(benchmark::State& state) {
  Bench b(int(state.range(0)));
  b.backward(b.forward());
  for (auto _ : state) b.backward(b.forward());
  b.label(state);
}
BENCHMARK(BM_ReprojectForwardBackward)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Device time per kernel (ms per call) from OpenCL events, with the queue serialised.
static void BM_ReprojectKernels(benchmark::State& state) {
  auto& rt = bench::runtime();
  Bench b(int(state.range(0)));
  b.backward(b.forward());
  const auto before = rt.profile();
  rt.set_profiling(true);
  for (auto _ : state) b.backward(b.forward());
  rt.set_profiling(false);
  for (const auto& [name, row] : rt.profile()) {
    if (name.rfind("render_reproject", 0) != 0) continue;
    const auto old = before.find(name);
    const double ms = row.total_ms - (old == before.end() ? 0.0 : old->second.total_ms);
    state.counters[name.substr(std::string("render_reproject_").size()) + "_ms"] =
        ms / double(state.iterations());
  }
  b.label(state);
}
BENCHMARK(BM_ReprojectKernels)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
