// Configuration of the multi-scale PatchGAN discriminator (method.md §4.3): architecture,
// leaky-ReLU slope, its own Adam, input depth normalisation, initialisation. Plain struct with
// defaults; a strict JSON reader (unknown keys are an error) and a writer for resolved configs.
//
// JSON section, every key optional:
//   {"scales": 2, "channels": [32, 64, 128], "strides": [2, 2, 1], "kernel": 4, "padding": 1,
//    "slope": 0.2, "lr": 2e-4, "beta1": 0.5, "beta2": 0.999, "eps": 1e-8,
//    "depth_scale_m": 80.0, "init_std": 0.02, "seed": 1}
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"

namespace sgnlf::adversarial {

struct PatchDiscriminatorConfig {
  int scales = 2;                         // input pyramid levels (2×2 average pooling), 1..3
  std::vector<int> channels{32, 64, 128};  // hidden conv layers, each followed by leaky ReLU
  std::vector<int> strides{2, 2, 1};       // one per hidden layer ("stride 2 then 1")
  int kernel = 4;                          // every layer, including the 1-channel logit layer
  int padding = 1;                         // zero padding; the logit layer has stride 1
  float slope = 0.2f;                      // leaky ReLU
  float lr = 2e-4f;                        // the discriminator's own Adam
  float beta1 = 0.5f;
  float beta2 = 0.999f;
  float eps = 1e-8f;
  float weight_decay = 0.0f;
  // Input depths in metres are divided by this (the sensor's range: inputs in [0, 1]); pixels
  // without a return are 0 in the input and stay 0.
  float depth_scale_m = 80.0f;
  float init_std = 0.02f;  // weights N(0, init_std²) (pix2pix), biases 0
  uint64_t seed = 1;

  // The keys and ranges (core/config_fields.hpp); the layer lists' sizes and entries and
  // padding's range [0, kernel − 1] are validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("scales", s.scales, 1, 3);
    v("channels", s.channels);
    v("strides", s.strides);
    v("kernel", s.kernel, 2, 5);
    v("padding", s.padding);
    v("slope", s.slope, 0.0f, 1.0f);
    v("lr", s.lr, 0.0f, 1.0f);
    v("beta1", s.beta1, 0.0f, 0.999999f);
    v("beta2", s.beta2, 0.0f, 0.999999f);
    v("eps", s.eps, 0.0f, 1.0f);
    v("weight_decay", s.weight_decay, 0.0f, 1.0f, config::omit_when(0.0f));
    v("depth_scale_m", s.depth_scale_m, 1e-3f, 1e4f);
    v("init_std", s.init_std, 1e-6f, 10.0f);
    v("seed", s.seed);
  }

  void validate(const std::string& where = "discriminator") const;  // throws ConfigError
  // Reads a "discriminator" section object; `where` names it in errors.
  static PatchDiscriminatorConfig from_json(const Json& section,
                                            const std::string& where = "discriminator");
  Json to_json() const;
};

// The size of the logits at `scale` (0: the input itself) for input images of h × w: pooled
// 2 × 2 `scale` times, then through every layer (kernel, stride, padding); (0, 0) when the image
// is too small for that (a pooled side below 2, or a layer's padded input below the kernel).
std::pair<int, int> discriminator_logit_size(const PatchDiscriminatorConfig& c, int scale, int h, int w);

// `c` fitted to input images of h × w, so that the discriminator runs on the image any sensor
// yields (a 16-beam head's 16 rows leave no logits at the second scale): the most scales up to
// c.scales whose logits all exist; when even one scale has none, the hidden layers' strides of
// 2 become 1 from the first layer on until it has. `c` itself when it fits. Throws ConfigError
// naming the image when nothing fits (an image smaller than the stride-1 layer stack).
PatchDiscriminatorConfig fit_discriminator_to_image(const PatchDiscriminatorConfig& c, int h, int w);

}  // namespace sgnlf::adversarial
