// The settings of a standalone training of Ψ on a surface (spectral_trainer.hpp, `sgnlf
// spectral --config`): Ψ's architecture and loss, steps, batch, Adam's learning rates and the
// seed. Host-only config (the trainer is the OpenCL part).
#pragma once
#include <cstdint>
#include <string>

#include "core/config_fwd.hpp"
#include "spectral/psi_spec.hpp"
#include "spectral/spectral_loss.hpp"

namespace sgnlf::spectral {

struct SpectralTrainConfig {
  PsiSpec psi;
  SpectralLossConfig loss;
  int steps = 1500;
  int batch = 2048;        // surface samples per step (×5 evaluations)
  double lr = 1e-2;
  double lr_final = 1e-2;  // final lr as a fraction of lr (cosine decay)
  uint64_t seed = 1;
  // The keys and ranges (core/config_fields.hpp); psi and loss are read, written and checked
  // by their own functions.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.object("psi", s.psi);
    v.object("loss", s.loss);
    v("steps", s.steps, 0, 10000000);
    v("batch", s.batch, 16, 1 << 22);
    v("lr", s.lr, 0.0, 1.0);
    v("lr_final", s.lr_final, 0.0, 1.0);
    v("seed", s.seed);
  }
  void validate() const;
  static SpectralTrainConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::spectral
