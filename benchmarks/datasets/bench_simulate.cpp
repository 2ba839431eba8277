// Simulation speed: rays per second of the LiDAR ray caster (one frame of a generated street)
// for the native HDL-64E / HDL-32E patterns and the one-ray-per-pixel grid, at 1 and 2 threads;
// and the time to grow a street world from a seed.
#include <benchmark/benchmark.h>

#include "core/config.hpp"
#include "datasets/sim_lidar.hpp"
#include "datasets/sim_street.hpp"

using namespace sgnlf;

namespace {

const sim::StreetWorld& world() {
  static const sim::StreetWorld w = [] {
    sim::StreetConfig c;
    c.seed = fnv1a64("bench");
    c.drive_length_m = 100;
    c.moving_vehicles = 4;
    return sim::generate_street(c);
  }();
  return w;
}

void BM_cast_scan(benchmark::State& st, const char* preset, const char* beams) {
  const Sensor s = sensor_preset(preset);
  sim::LidarModel m;
  m.beams = beams;
  const int threads = int(st.range(0));
  sim::StreetWorld w = world();
  w.place_movers(1.0);
  sim::DriveConfig dc;
  const auto T = sim::drive(w, dc, {2.0}).front();
  size_t rays = 0;
  uint32_t frame = 0;
  for (auto _ : st) {
    sim::DropStats ds;
    auto pts = sim::cast_scan(w.scene, s, T, m, 1, frame++, threads, &ds);
    benchmark::DoNotOptimize(pts.data());
    rays += ds.rays;
  }
  st.counters["rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

void BM_generate_street(benchmark::State& st) {
  uint64_t seed = 1;
  for (auto _ : st) {
    sim::StreetConfig c;
    c.seed = seed++;
    c.drive_length_m = 190;
    auto w = sim::generate_street(c);
    benchmark::DoNotOptimize(w.scene.primitives().data());
  }
}

}  // namespace

BENCHMARK_CAPTURE(BM_cast_scan, kitti360_native, "kitti360", "native")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_cast_scan, kitti360_grid, "kitti360", "grid")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_cast_scan, nuscenes_native, "nuscenes", "native")->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_generate_street)->Unit(benchmark::kMillisecond);
