// Microbenchmarks of the conv stack (runtime/conv) at the PatchGAN's layer shapes and of the
// discriminator step (runtime/adversarial), at the sensors' full range-image sizes: 66 × 1030
// (kitti360-like) and 32 × 1080 (nuScenes-like), one [real; fake] pair batch = 2 images.
// Each reports GFLOP/s (2 per multiply-add) and frac_peak_flops, the fraction of the float16
// FMA peak measured in the same run (harness roofline probes); cpu_s = process CPU seconds per
// iteration. Time per iteration = enqueue of the pass + clFinish (launch overheads included).
// Medians: --benchmark_repetitions=5 --benchmark_report_aggregates_only=true.
#include <string>
#include <vector>

#include "adversarial/patch_discriminator.hpp"
#include "bench_timing.hpp"
#include "conv_shapes.hpp"
#include "conv/conv2d.hpp"

using namespace sgnlf;
using bench::run_timed;
using bench::uniform;

namespace {
using bench::Image;
using bench::kImages;
using bench::patchgan_layers;

void conv_layer(benchmark::State& state, Image img, int scale, int layer, bool backward) {
  auto& rt = bench::runtime();
  const auto lc = patchgan_layers(img.h, img.w, scale)[size_t(layer)];
  conv::Conv2d cv(rt, lc.spec);
  const int n = 2;
  const auto& s = lc.spec;
  const int ho = s.out_size(lc.h), wo = s.out_size(lc.w);
  std::vector<float> params(cv.n_params());
  cv.init_params(params, 0, 1, 0.02f);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_in = cl::Buffer::from(rt, uniform(size_t(n) * lc.h * lc.w * s.input_cs(), 0, 1, 2));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * ho * wo * s.out_cs(), -1, 1, 3));
  cl::Buffer b_out(rt, size_t(n) * ho * wo * s.out_cs() * 4), b_g(rt, params.size() * 4),
      b_din(rt, size_t(n) * lc.h * lc.w * s.input_cs() * 4);
  const double secs = run_timed(state, [&] {
    if (backward)
      cv.backward(b_p, 0, b_in, n, lc.h, lc.w, b_d, &b_g, 0, &b_din);
    else
      cv.forward(b_p, 0, b_in, n, lc.h, lc.w, b_out);
  });
  // Useful FLOPs only (the 1-channel logit layer computes 16 padded lanes).
  const double flops = 2.0 * s.macs(n, lc.h, lc.w) * (backward ? 2.0 : 1.0);
  bench::set_roofline_counters(state, secs, flops, 0);
  state.SetLabel(std::to_string(s.c_in) + "->" + std::to_string(s.c_out) + " k" +
                 std::to_string(s.kernel) + " s" + std::to_string(s.stride) + " in " +
                 std::to_string(lc.h) + "x" + std::to_string(lc.w) + " x2");
}

// One discriminator step (forward of the 2-image batch, hinge, backward, Adam) or one
// generator-term pass (forward of the fake, backward to the input), default config.
void disc_pass(benchmark::State& state, Image img, bool generator) {
  auto& rt = bench::runtime();
  const adversarial::PatchDiscriminatorConfig cfg;
  adversarial::PatchDiscriminator D(rt, cfg);
  const int n = 1;
  const size_t floats = size_t(n) * img.h * img.w * 2;
  auto b_real = cl::Buffer::from(rt, uniform(floats, 1, 80, 4));
  auto b_fake = cl::Buffer::from(rt, uniform(floats, 1, 80, 5));
  cl::Buffer b_d(rt, floats * 4);
  const double secs = run_timed(state, [&] {
    if (generator)
      D.generator_grad(b_fake, n, img.h, img.w, b_d);
    else
      D.step(b_real, b_fake, n, img.h, img.w);
  });
  const int images = generator ? n : 2 * n;
  // Forward + input backward + (step only) weight backward, 2 FLOPs per multiply-add.
  const double flops = 2.0 * D.forward_macs(images, img.h, img.w) * (generator ? 2.0 : 3.0);
  bench::set_roofline_counters(state, secs, flops, 0);
  state.counters["params"] = double(D.n_params());
}

const bool registered = [] {
  for (const auto& img : kImages) {
    for (int scale = 0; scale < 2; ++scale)
      for (int layer = 0; layer < 4; ++layer)
        for (bool bwd : {false, true}) {
          const std::string name = std::string("BM_PatchGanConv") + (bwd ? "Bwd" : "Fwd") + "/" +
                                   img.name + "/scale" + std::to_string(scale) + "/layer" +
                                   std::to_string(layer);
          benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
            conv_layer(s, img, scale, layer, bwd);
          })->UseManualTime()->Unit(benchmark::kMillisecond);
        }
    benchmark::RegisterBenchmark((std::string("BM_DiscriminatorStep/") + img.name).c_str(),
                                 [=](benchmark::State& s) { disc_pass(s, img, false); })
        ->UseManualTime()->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((std::string("BM_DiscriminatorGeneratorGrad/") + img.name).c_str(),
                                 [=](benchmark::State& s) { disc_pass(s, img, true); })
        ->UseManualTime()->Unit(benchmark::kMillisecond);
  }
  return true;
}();
}  // namespace
