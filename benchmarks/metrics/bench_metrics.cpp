// Host metrics on a KITTI-360-sized frame (66×1030, ~60 k points per side): Chamfer/F-score
// (k-d tree), SSIM, and the whole evaluate_view. Wall-clock time (no device involved).
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/config.hpp"
#include "core/rng.hpp"
#include "metrics/chamfer.hpp"
#include "metrics/evaluate.hpp"
#include "metrics/ssim.hpp"

using namespace sgnlf;
using namespace sgnlf::metrics;

namespace {

// A street-like frame: ground plane 1.73 m below the sensor, walls 8–40 m away depending on
// azimuth; 3 % of rays dropped. `noise` perturbs ranges (the "prediction").
RangeImage street_frame(const Sensor& s, uint64_t seed, float noise) {
  Rng rng(seed);
  RangeImage img(s.height, s.width);
  for (int r = 0; r < s.height; ++r)
    for (int c = 0; c < s.width; ++c) {
      const size_t i = img.idx(r, c);
      if (rng.uniform() < 0.03f) continue;
      const Eigen::Vector3f d = pixel_direction(s, r, c);
      const float az = std::atan2(d.y(), d.x());
      const float wall =
          8.f + 32.f * (0.5f + 0.5f * std::sin(3.f * az)) + 0.5f * std::sin(40.f * az);
      float range = wall / std::max(1e-3f, std::hypot(d.x(), d.y()));
      if (d.z() < 0.f) range = std::min(range, 1.73f / -d.z());
      range += noise * (rng.uniform() - 0.5f);
      if (range >= 80.f) continue;
      img.range[i] = range;
      img.intensity[i] = rng.uniform();
      img.ray_drop[i] = 1.f;
    }
  return img;
}

std::vector<geometry::Point3f> points_of(const Sensor& s, const RangeImage& img) {
  std::vector<geometry::Point3f> out;
  for (const auto& p : unproject(s, img)) out.emplace_back(p.x, p.y, p.z);
  return out;
}

void BM_ChamferFscore(benchmark::State& state) {
  const Sensor s = sensor_preset("kitti360");
  const auto gt = points_of(s, street_frame(s, 1, 0.f));
  const auto pred = points_of(s, street_frame(s, 2, 0.2f));
  double cd = 0;
  for (auto _ : state) {
    ChamferResult r = chamfer_fscore(pred, gt);
    benchmark::DoNotOptimize(r);  // not on the double: "+r" on a double misbehaves here
    cd = r.cd;
  }
  state.counters["n_pred"] = double(pred.size());
  state.counters["n_gt"] = double(gt.size());
  state.counters["cd_m2"] = cd;
}
BENCHMARK(BM_ChamferFscore)->Unit(benchmark::kMillisecond);

void BM_Ssim(benchmark::State& state) {
  const Sensor s = sensor_preset("kitti360");
  const RangeImage a = street_frame(s, 1, 0.f), b = street_frame(s, 2, 0.2f);
  const std::vector<double> x(a.range.begin(), a.range.end()), y(b.range.begin(), b.range.end());
  for (auto _ : state) benchmark::DoNotOptimize(ssim(x, y, s.height, s.width, 80.0));
  state.SetItemsProcessed(state.iterations() * int64_t(x.size()));
}
BENCHMARK(BM_Ssim)->Unit(benchmark::kMillisecond);

void BM_EvaluateView(benchmark::State& state) {
  const Sensor s = sensor_preset("kitti360");
  const RangeImage gt = street_frame(s, 1, 0.f), pred = street_frame(s, 2, 0.2f);
  for (auto _ : state) benchmark::DoNotOptimize(evaluate_view(s, pred, gt));
}
BENCHMARK(BM_EvaluateView)->Unit(benchmark::kMillisecond);

}  // namespace
