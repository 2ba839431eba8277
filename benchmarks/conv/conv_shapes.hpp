// The convolution layer shapes the conv-stack benchmarks run (bench_conv.cpp,
// bench_conv_gemm.cpp): the default PatchGAN discriminator's layers (runtime/adversarial,
// PatchDiscriminatorConfig) and the default ray-drop U-Net's (runtime/refine/ray_drop_unet.cpp,
// RayDropUNetConfig), at the sensors' full range-image sizes.
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "adversarial/patch_discriminator_config.hpp"
#include "conv/conv2d.hpp"
#include "refine/ray_drop_unet_config.hpp"

namespace sgnlf::bench {

struct Image {
  const char* name;
  int h, w;
};
constexpr Image kImages[] = {{"kitti360_66x1030", 66, 1030}, {"nuscenes_32x1080", 32, 1080}};

// One convolution of a network: its spec, the input size it sees and the batch it runs on.
struct LayerCase {
  conv::Conv2dSpec spec;
  int h, w;
  int n = 1;
  std::string name;
};

// The default PatchGAN's layers at `scale` (input pooled `scale` times) of an h × w image, on
// the [real; fake] pair batch (n = 2).
inline std::vector<LayerCase> patchgan_layers(int h, int w, int scale) {
  const adversarial::PatchDiscriminatorConfig cfg;
  std::vector<LayerCase> out;
  h >>= scale;
  w >>= scale;
  int c_in = 2;
  for (size_t l = 0; l <= cfg.channels.size(); ++l) {
    conv::Conv2dSpec s;
    s.c_in = c_in;
    s.c_out = l < cfg.channels.size() ? cfg.channels[l] : 1;
    s.kernel = cfg.kernel;
    s.stride = l < cfg.channels.size() ? cfg.strides[l] : 1;
    s.pad = cfg.padding;
    out.push_back({s, h, w, 2, "patchgan" + std::to_string(l)});
    h = s.out_size(h);
    w = s.out_size(w);
    c_in = s.c_out;
  }
  return out;
}

// The default ray-drop U-Net's distinct convolutions on one h × w image (ray_drop_unet.cpp:
// e_l has channels·2^min(l, depth − 1) channels at h / 2^l; the up stage at level 0 keeps its
// concatenation [e_0, up2(d_1)] in its first conv): the 1×1 in-conv, the first down stage's
// first conv, the bottleneck's second conv, the full-resolution up stage's two convs and the
// 1×1 logit conv. Each input is a conv-stack tensor of exactly c_in channels (in_cs = c_in).
inline std::vector<LayerCase> unet_layers(int h, int w) {
  const refine::RayDropUNetConfig cfg;
  auto width = [&](int l) { return cfg.channels << std::min(l, cfg.depth - 1); };
  auto conv = [](int c_in, int c_out, int k) {
    conv::Conv2dSpec s;
    s.c_in = c_in;
    s.c_out = c_out;
    s.kernel = k;
    s.stride = 1;
    s.pad = k / 2;
    s.in_cs = c_in;
    return s;
  };
  const int cat0 = width(0) + width(0);  // [e_0, up2(d_1)], d_1 ends with e_0's width
  const int hd = h >> cfg.depth, wd = w >> cfg.depth;
  return {{conv(3, width(0), 1), h, w, 1, "unet_in"},
          {conv(width(0), width(1), 3), h / 2, w / 2, 1, "unet_down1a"},
          {conv(width(cfg.depth), width(cfg.depth), 3), hd, wd, 1, "unet_bottleneck"},
          {conv(cat0, cat0, 3), h, w, 1, "unet_up0a"},
          {conv(cat0, width(0), 3), h, w, 1, "unet_up0b"},
          {conv(width(0), 1, 1), h, w, 1, "unet_out"}};
}

}  // namespace sgnlf::bench
