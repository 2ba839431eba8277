// A table run with fake hooks (no training, no data): deterministic numbers the harness tests
// check by hand. lidar-nerf and sg-nlf "run"; the other rows are not implemented.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

#include "harness/runner.hpp"

namespace sgnlf::test {

// Metrics of the fake lidar-nerf on sequence k (0-based): cd = 0.1 + 0.02 k, depth_psnr =
// 20 + k, intensity_psnr = 15 − k, fscore = 0.9; sg-nlf: cd halved, psnr + 2.
// Each run reports 6 repetitions of "step" timings (0.010 s … 0.015 s) and a train time.
// With `seed_noise`, seed s adds 0.01 (s − 1) to cd and to depth_psnr (a spread over seeds).
inline harness::BenchHooks fake_hooks(int* prepare_calls = nullptr, bool fail_sg_nlf = false,
                                      bool seed_noise = false) {
  harness::BenchHooks h;
  h.implemented = [](const std::string& m) { return m == "lidar-nerf" || m == "sg-nlf"; };
  h.prepare = [prepare_calls](const harness::SequenceDef& s, const harness::BenchOptions&,
                              const std::string& dir) {
    if (prepare_calls) ++*prepare_calls;
    harness::PreparedSequence p;
    p.dataset_dir = dir;
    p.dataset = Json{{"name", s.name}, {"frames", 16}, {"test", {13}}, {"seed", 1}};
    return p;
  };
  h.run = [fail_sg_nlf, seed_noise](const pipeline::MethodRequest& r) {
    if (fail_sg_nlf && r.method == "sg-nlf") throw Error("fake divergence");
    const int k = r.dataset_dir.find("1728") != std::string::npos ? 1 : 0;
    const double f = r.method == "sg-nlf" ? 0.5 : 1.0;
    const double g = r.method == "sg-nlf" ? 2.0 : 0.0;
    const double e = seed_noise ? 0.01 * double(r.seed - 1) : 0.0;
    pipeline::MethodResult res;
    res.config = Json{{"method", r.method}, {"iterations", 10}, {"seed", r.seed}};
    res.metrics = Json{{"cd", f * (0.1 + 0.02 * k) + e}, {"depth_psnr", 20.0 + k + g + e},
                       {"intensity_psnr", 15.0 - k + g}, {"fscore", 0.9},
                       {"depth_lpips", nullptr}};
    res.per_frame = Json::array({Json{{"frame", 13}, {"cd", f * (0.1 + 0.02 * k)}}});
    res.pose_metrics = r.method == "sg-nlf" ? Json{{"ate_m", 0.07}} : Json(nullptr);
    res.extra = Json{{"naive_baseline", {{"cd", 0.2 + 0.1 * k}, {"depth_psnr", 18.0}}}};
    res.timings = Json{{"train", 1.0 + k}, {"step", {0.010, 0.011, 0.012, 0.013, 0.014, 0.015}}};
    return res;
  };
  return h;
}

inline Json fake_context() {
  return Json{{"opencl", {{"device", "fake-device"}, {"driver_version", "1.0"}}},
              {"git", {{"sha", "0123456789abcdef0123456789abcdef01234567"}, {"dirty", false}}}};
}

// The kitti360-standard smoke table's options, seed 7 (or `seeds`), writing nothing.
inline harness::BenchOptions fake_options(std::vector<uint64_t> seeds = {}) {
  harness::BenchOptions o;
  o.table = "kitti360-standard";
  o.scale = "smoke";
  o.out_dir = "/nonexistent/out";
  o.seed = 7;
  o.seeds = std::move(seeds);
  return o;
}

inline Json fake_results(bool fail_sg_nlf = false, int* prepare_calls = nullptr) {
  return harness::run_table(fake_options(), fake_hooks(prepare_calls, fail_sg_nlf), fake_context());
}

// The row of `method` in a results JSON (std::out_of_range when there is none).
inline Json& row(Json& r, const std::string& method) {
  for (auto& x : r.at("rows"))
    if (x.at("method") == method) return x;
  throw std::out_of_range("no row " + method);
}

}  // namespace sgnlf::test
