// Configuration of SG-NLF's hybrid field (method.md §4.1), the config's "spectral" section:
// Ψ's architecture and loss, the fusion ramp λ(t), and the schedule on which Ψ trains on
// area-uniform samples of the current surface during pose-free training
// (spectral_schedule.hpp). Present only in the configs of methods built on the hybrid field
// (ConfigSections::spectral, methods/), so other methods' config hashes do not change; on exactly
// when present (absent: the plain hash grid, the ablation "without hybrid").
#pragma once
#include "core/config_fwd.hpp"
#include "spectral/fusion_ramp.hpp"
#include "spectral/psi_spec.hpp"
#include "spectral/spectral_loss.hpp"

namespace sgnlf::pipeline {

struct SpectralFieldConfig {
  spectral::PsiSpec psi;             // 3 → 64 → 64 → K, tanh
  spectral::SpectralLossConfig loss; // Ky Fan form, β, h
  spectral::FusionRamp fusion;       // λ: 0 → 1 between these training iterations
  int every = 1;                     // one spectral step every `every` training steps
  int batch = 1024;                  // surface samples per spectral step (× 5 evaluations)
  double lr = 1e-2, lr_final = 0.1;  // Ψ's Adam: lr cosine-decayed to lr·lr_final
  int points_per_frame = 2000;       // observed points per training frame in the surface pool
  double radius_m = 1.0;             // neighbourhood of the uniform-area thinning and the PCA
                                     // normals (spectral::surface_from_points), metres
  // false: the field without the hash grid, Ψ(x) alone feeds the density MLP (the ablation
  // "spectral only", method.md §5); written only when false, so the other configs keep their hash.
  bool geometric = true;
  // The keys and ranges (core/config_fields.hpp).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.object("psi", s.psi);
    v.object("loss", s.loss);
    v.object("fusion", s.fusion);
    v("every", s.every, 1, 1000000);
    v("batch", s.batch, 16, 1 << 20);
    v("lr", s.lr, 0.0, 1.0);
    v("lr_final", s.lr_final, 0.0, 1.0);
    v("points_per_frame", s.points_per_frame, 16, 1 << 22);
    v("radius_m", s.radius_m, 1e-3, 100.0);
    v("geometric", s.geometric, config::omit_when(true));
  }

  void validate(const std::string& where) const;
  static SpectralFieldConfig from_json(ConfigReader& r);  // reads "spectral"; errors name r.where()
  void to_json(Json& j) const;                            // adds the "spectral" section
  double lr_at(long step, long iterations) const;         // cosine decay
};

}  // namespace sgnlf::pipeline
