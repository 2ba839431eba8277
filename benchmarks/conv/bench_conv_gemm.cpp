// The convolutions' two GEMM variants of the device profiles (cl::GemmVariant) on the same
// shapes: cpu_tiles (kernels/conv/conv2d.cl and conv2d_narrow.cl, the "cpu" profile's) and
// local_tiles (kernels/conv/conv2d_tiles.cl, the "gpu" profile's), set over the Runtime's
// profile while the Conv2d is made, as BM_MlpGemm* in bench_field does for the MLP. Each pass
// alone: the forward, the input backward (d_in only) and the weight gradient (dW and db only),
// on the default PatchGAN's layers (the [real; fake] pair batch of the 66 × 1030 image, scale
// 0) and the default ray-drop U-Net's distinct convolutions (one 66 × 1030 image)
// (conv_shapes.hpp). Names: BM_ConvGemm{Fwd,BwdIn,BwdWgt}/<layer>/<variant>.
// Each reports GFLOP/s (2 per multiply-add of the layer, the same for the three passes) and
// frac_peak_flops, the fraction of the float16 FMA peak measured in the same run; cpu_s =
// process CPU seconds per iteration. Time per iteration = enqueue of the pass + clFinish.
// scripts/gpu-check.sh runs them (bench_conv:BM_ConvGemm).
#include <string>
#include <vector>

#include "bench_timing.hpp"
#include "cl/device_profile.hpp"
#include "conv/conv2d.hpp"
#include "conv_shapes.hpp"

using namespace sgnlf;
using bench::LayerCase;
using bench::run_timed;
using bench::uniform;

namespace {
enum class Pass { Fwd, BwdIn, BwdWgt };
const char* pass_name(Pass p) {
  return p == Pass::Fwd ? "Fwd" : p == Pass::BwdIn ? "BwdIn" : "BwdWgt";
}

void conv_gemm(benchmark::State& state, const LayerCase& lc, Pass pass, cl::GemmVariant gemm) {
  auto& rt = bench::runtime();
  const cl::DeviceProfile saved = rt.device_profile();
  cl::DeviceProfile p = saved;
  p.gemm = gemm;
  rt.set_device_profile(p);
  conv::Conv2d cv(rt, lc.spec);  // reads the profile here
  rt.set_device_profile(saved);
  const auto& s = lc.spec;
  const int n = lc.n, ho = s.out_size(lc.h), wo = s.out_size(lc.w);
  std::vector<float> params(cv.n_params());
  cv.init_params(params, 0, 1, 0.02f);
  auto b_p = cl::Buffer::from(rt, params);
  const size_t in_floats = size_t(n) * lc.h * lc.w * s.input_cs();
  const size_t out_floats = size_t(n) * ho * wo * s.out_cs();
  auto b_in = cl::Buffer::from(rt, uniform(in_floats, 0, 1, 2));
  auto d_out = uniform(out_floats, -1, 1, 3);
  for (size_t i = 0; i < d_out.size(); ++i)  // Conv2d::backward: padding channels zero
    if (int(i % size_t(s.out_cs())) >= s.c_out) d_out[i] = 0.0f;
  auto b_d = cl::Buffer::from(rt, d_out);
  cl::Buffer b_out(rt, out_floats * 4), b_g(rt, params.size() * 4), b_din(rt, in_floats * 4);
  const double secs = run_timed(state, [&] {
    if (pass == Pass::Fwd)
      cv.forward(b_p, 0, b_in, n, lc.h, lc.w, b_out);
    else if (pass == Pass::BwdIn)
      cv.backward(b_p, 0, b_in, n, lc.h, lc.w, b_d, nullptr, 0, &b_din);
    else
      cv.backward(b_p, 0, b_in, n, lc.h, lc.w, b_d, &b_g, 0, nullptr);
  });
  // Useful FLOPs only (padded output channels are not counted).
  bench::set_roofline_counters(state, secs, 2.0 * s.macs(n, lc.h, lc.w), 0);
  state.SetLabel(std::string(cl::gemm_name(gemm)) + " " + std::to_string(s.c_in) + "->" +
                 std::to_string(s.c_out) + " k" + std::to_string(s.kernel) + " s" +
                 std::to_string(s.stride) + " in " + std::to_string(lc.h) + "x" +
                 std::to_string(lc.w) + " x" + std::to_string(n));
}

const bool registered = [] {
  const bench::Image img = bench::kImages[0];  // kitti360_66x1030
  std::vector<LayerCase> layers = bench::patchgan_layers(img.h, img.w, 0);
  for (const auto& l : bench::unet_layers(img.h, img.w)) layers.push_back(l);
  for (Pass pass : {Pass::Fwd, Pass::BwdIn, Pass::BwdWgt})
    for (const auto& lc : layers)
      for (auto gemm : {cl::GemmVariant::CpuTiles, cl::GemmVariant::LocalTiles}) {
        const std::string name = std::string("BM_ConvGemm") + pass_name(pass) + "/" + lc.name +
                                 "/" + cl::gemm_name(gemm);
        benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
          conv_gemm(s, lc, pass, gemm);
        })->UseManualTime()->Unit(benchmark::kMillisecond);
      }
  return true;
}();
}  // namespace
