// Microbenchmarks of the ray-drop U-Net's layer kernels (runtime/conv: max pool, bilinear ×2
// upsampling into the concatenation, skip copy and split, sigmoid + BCE, box mask) at the
// default U-Net's full-resolution shapes (channels 32: level 0 of a 66 × 1030 kitti360-like or
// 32 × 1080 nuScenes-like image), and of one training step and one inference pass of the
// default RayDropUNet (runtime/refine) on one such image.
// The layer kernels are memory-bound: each reports GB/s of the bytes it must move (each input
// read once, each output written once) and frac_peak_bw, the fraction of the triad bandwidth
// measured in the same run. The U-Net passes report GFLOP/s of their convolutions (2 per
// multiply-add; a step = forward + input and weight backward = 3 forwards) and frac_peak_flops.
// Medians: --benchmark_repetitions=5 --benchmark_report_aggregates_only=true.
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "conv/bce_loss.hpp"
#include "conv/box_mask.hpp"
#include "conv/channel_copy.hpp"
#include "conv/max_pool.hpp"
#include "conv/upsample.hpp"
#include "refine/ray_drop_unet.hpp"

using namespace sgnlf;
using bench::run_timed;
using bench::uniform;

namespace {
struct Image {
  const char* name;
  int h, w;
};
constexpr Image kImages[] = {{"kitti360_66x1030", 66, 1030}, {"nuscenes_32x1080", 32, 1080}};
constexpr int kC = 32;  // the default U-Net's level-0 width
constexpr double kF = sizeof(float);

cl::Buffer random_buffer(size_t floats, uint64_t seed) {
  return cl::Buffer::from(bench::runtime(), uniform(floats, -1.0f, 1.0f, seed));
}

void maxpool(benchmark::State& state, Image img, bool backward) {
  conv::MaxPool2x2 pool(bench::runtime());
  const conv::PoolShape s{1, img.h, img.w, kC, kC, kC};
  const double full = double(img.h) * img.w * kC, quarter = double(s.out_h()) * s.out_w() * kC;
  auto in = random_buffer(size_t(full), 1), out = random_buffer(size_t(quarter), 2);
  auto d_in = random_buffer(size_t(full), 3);
  const double secs = run_timed(state, [&] {
    if (backward)
      pool.backward(s, in, out, d_in, true);  // accumulating, as into the skip's gradient
    else
      pool.forward(s, in, out);
  });
  bench::set_roofline_counters(state, secs, 0, kF * (backward ? 3 * full + quarter : full + quarter));
}

void upsample(benchmark::State& state, Image img, bool backward) {
  conv::Upsample2x up(bench::runtime());
  // d_1 (h/2 × w/2 × 32) into the second half of level 0's 64-channel concatenation.
  const conv::UpsampleShape s{1, img.h / 2, img.w / 2, kC, kC, img.h, img.w, 2 * kC, kC};
  const double small = double(s.h) * s.w * kC, big = double(s.th) * s.tw * kC;
  auto in = random_buffer(size_t(small), 4), cat = random_buffer(size_t(2 * big), 5);
  const double secs = run_timed(state, [&] {
    if (backward)
      up.backward(s, cat, in, false);
    else
      up.forward(s, in, cat);
  });
  bench::set_roofline_counters(state, secs, 0, kF * (small + big));
}

void skip_copy(benchmark::State& state, Image img, bool split) {
  conv::ChannelCopy copy(bench::runtime());
  const int pix = img.h * img.w;
  auto e = random_buffer(size_t(pix) * kC, 6), cat = random_buffer(size_t(pix) * 2 * kC, 7);
  const conv::ChannelCopyShape fwd{pix, kC, kC, 0, 2 * kC, 0}, back{pix, kC, 2 * kC, 0, kC, 0};
  const double secs = run_timed(state, [&] {
    if (split)
      copy.run(back, cat, e, false);
    else
      copy.run(fwd, e, cat, false);
  });
  bench::set_roofline_counters(state, secs, 0, kF * 2.0 * pix * kC);
}

void bce(benchmark::State& state, Image img) {
  auto& rt = bench::runtime();
  conv::BceWithLogits loss(rt);
  const int count = img.h * img.w;
  auto logits = random_buffer(size_t(count) * 16, 8), d = random_buffer(size_t(count) * 16, 9);
  auto target = cl::Buffer::from(rt, uniform(size_t(count), 0.0f, 1.0f, 10));
  auto losses = random_buffer(1, 11);
  const double secs = run_timed(state, [&] { loss.loss_grad(logits, count, 16, target, d, losses, 0); });
  // Logit and target read, the padded gradient row (16 floats) written.
  bench::set_roofline_counters(state, secs, 0, kF * count * (1.0 + 1.0 + 16.0));
}

void box_mask(benchmark::State& state, Image img) {
  auto& rt = bench::runtime();
  conv::BoxMask mask(rt);
  const conv::BoxMaskShape s{1, img.h, img.w, 3, 3, 3};
  const double floats = double(img.h) * img.w * 3;
  auto in = random_buffer(size_t(floats), 12), out = random_buffer(size_t(floats), 13);
  auto scale = cl::Buffer::from(rt, std::vector<float>{1.0f, 1.0f, 0.0125f});
  std::vector<int> boxes;  // 16 boxes (LiDAR4D's mean count), 10 % of the image at most
  for (int b = 0; b < 16; ++b) boxes.insert(boxes.end(), {b % 50, 60 * b, b % 50 + 5, 60 * b + 90});
  auto b_boxes = cl::Buffer::from(rt, boxes);
  const double secs = run_timed(state, [&] { mask.run(s, scale, b_boxes, 0, 16, in, out); });
  bench::set_roofline_counters(state, secs, 0, kF * 2.0 * floats);
}

// One full-batch training step (box mask, forward, BCE, backward, Adam) or one inference pass
// of the default U-Net (channels 32, depth 4) on one image.
void unet_pass(benchmark::State& state, Image img, bool train) {
  auto& rt = bench::runtime();
  refine::RayDropUNet net(rt, refine::RayDropUNetConfig{});
  const size_t pix = size_t(img.h) * img.w;
  auto in = cl::Buffer::from(rt, uniform(pix * 3, 0.0f, 1.0f, 14));
  auto masks = cl::Buffer::from(rt, uniform(pix, 0.0f, 1.0f, 15));
  cl::Buffer probs(rt, pix * sizeof(float)), losses(rt, sizeof(float));
  auto boxes = cl::Buffer::from(rt, std::vector<int>{1, 1, 5, 90});
  const double secs = run_timed(state, [&] {
    if (train)
      net.step(in, masks, 1, img.h, img.w, boxes, 0, 1, 1e-3f, losses, 0);
    else
      net.forward(in, 1, img.h, img.w, probs);
  });
  const double flops = 2.0 * net.forward_macs(1, img.h, img.w) * (train ? 3.0 : 1.0);
  bench::set_roofline_counters(state, secs, flops, 0);
  state.counters["params"] = double(net.n_params());
}

template <typename F>
void add(const std::string& name, F f) {
  benchmark::RegisterBenchmark(name.c_str(), f)->UseManualTime()->Unit(benchmark::kMillisecond);
}

const bool registered = [] {
  for (const auto& img : kImages) {
    const std::string tail = std::string("/") + img.name;
    for (bool bwd : {false, true}) {
      const std::string dir = bwd ? "Bwd" : "Fwd";
      add("BM_UNetMaxPool" + dir + tail, [=](benchmark::State& s) { maxpool(s, img, bwd); });
      add("BM_UNetUpsample" + dir + tail, [=](benchmark::State& s) { upsample(s, img, bwd); });
      add(std::string("BM_UNetSkip") + (bwd ? "Split" : "Copy") + tail,
          [=](benchmark::State& s) { skip_copy(s, img, bwd); });
    }
    add("BM_UNetBce" + tail, [=](benchmark::State& s) { bce(s, img); });
    add("BM_UNetBoxMask" + tail, [=](benchmark::State& s) { box_mask(s, img); });
    add("BM_RayDropUNetForward" + tail, [=](benchmark::State& s) { unet_pass(s, img, false); });
    add("BM_RayDropUNetStep" + tail, [=](benchmark::State& s) { unet_pass(s, img, true); });
  }
  return true;
}();
}  // namespace
