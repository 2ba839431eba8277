// Throughput of the LiDAR odometry (odometry/lidar_odometry.hpp) over whole sequences, in
// scans per second (items_per_second): nuScenes-size scans (HDL-32E, ~35 k points: simulated
// nuscenes-low-a and the real scene-0916 keyframes) and HDL-64E scans (simulated kitti360-1538
// at 10 Hz, ~60 k points, and the real KITTI odometry slice, ~120 k points). Real data is read
// from $SGNLF_SHARED_DIR/data/real (else ../shared beside the checkout) and skipped when absent.
// Targets: ≥ 20 scans/s nuScenes-size, ≥ 10 scans/s HDL-64E on 2 cores.
// Arg: threads of the registration.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>

#include "datasets/loader.hpp"
#include "datasets/simulate.hpp"
#include "odometry/trajectory.hpp"

using namespace sgnlf;

namespace {

std::string real_dir() {
  const char* e = std::getenv("SGNLF_SHARED_DIR");
  return (e ? std::string(e) : std::string(SGNLF_SHARED_DIR)) + "/data/real";
}

const Dataset* dataset(const std::string& name) {
  static std::map<std::string, Dataset> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return &it->second;
  Dataset d;
  if (name == "nuscenes-low-a" || name == "kitti360-1538") {
    SimOptions o;
    o.sequence = name;
    o.frames = name == "kitti360-1538" ? 64 : 36;
    o.threads = 2;
    d = simulate_dataset(o);
  } else if (name == "real-nuscenes") {
    const std::string p = real_dir() + "/nuscenes-mini-scene-0916";
    if (!std::filesystem::exists(p)) return nullptr;
    LoadOptions lo;
    lo.sequence = "scene-0916";
    lo.frames = 36;
    d = load_dataset(p, lo);
  } else if (name == "real-kitti") {
    const std::string p = real_dir() + "/kitti-odometry-00-slice";
    if (!std::filesystem::exists(p)) return nullptr;
    LoadOptions lo;
    lo.start = 40;
    lo.frames = 10;
    d = load_dataset(p, lo);
  }
  return &cache.emplace(name, std::move(d)).first->second;
}

void run(benchmark::State& state, const std::string& name) {
  const Dataset* d = dataset(name);
  if (!d) {
    state.SkipWithError(("no data for " + name + " under " + real_dir()).c_str());
    return;
  }
  std::vector<const std::vector<PointXYZI>*> scans;
  std::vector<double> t;
  double points = 0;
  for (const auto& f : d->frames) {
    scans.push_back(&f.points);
    t.push_back(f.timestamp_s);
    points += double(f.points.size());
  }
  odometry::OdometryConfig cfg;
  cfg.threads = int(state.range(0));
  size_t failed = 0;
  for (auto _ : state) {
    const auto r = odometry::estimate_trajectory(scans, t, cfg);
    failed = r.failed.size();
    benchmark::DoNotOptimize(r.T_world_lidar.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(scans.size()));
  state.counters["scans"] = double(scans.size());
  state.counters["points_per_scan"] = points / double(scans.size());
  state.counters["failed"] = double(failed);
}

}  // namespace

BENCHMARK_CAPTURE(run, nuscenes_low_a_sim, std::string("nuscenes-low-a"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run, nuscenes_scene0916_real, std::string("real-nuscenes"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run, kitti360_1538_sim_hdl64, std::string("kitti360-1538"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(run, kitti_00_real_hdl64, std::string("real-kitti"))
    ->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
