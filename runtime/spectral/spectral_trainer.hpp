// Standalone training of Ψ on a surface (method.md §4.1): per step a fresh area-uniform batch,
// the spectral objective, Adam (the field's kernel) with lr cosine-decayed from `lr` to
// lr·lr_final; at the end the Rayleigh–Ritz readout on a large evaluation set folded into Ψ's
// last layer. Ψ owns its own flat parameter buffer here; inside the full model the pipeline puts
// Ψ in its slice of the model buffer and calls SpectralObjective directly.
#pragma once
#include <functional>

#include "field/adam.hpp"
#include "spectral/psi.hpp"
#include "spectral/spectral_objective.hpp"
#include "spectral/spectral_train_config.hpp"

namespace sgnlf::spectral {

// Draws `n` surface samples (weights summing to 1).
using SurfaceSampler = std::function<std::vector<SurfacePoint>(Rng& rng, size_t n)>;

struct SpectralTrainSummary {
  int steps = 0;
  double first_loss = 0, final_loss = 0;
  std::vector<double> loss_curve;  // every step
};

class SpectralTrainer {
 public:
  SpectralTrainer(cl::Runtime& rt, const SpectralTrainConfig& cfg);

  // Runs cfg.steps steps; `on_step(step, loss)` is called after each (may be empty).
  SpectralTrainSummary train(const SurfaceSampler& sampler,
                             const std::function<void(int, double)>& on_step = {});
  // One step with a given batch at learning rate lr; returns the loss.
  double step(const std::vector<SurfacePoint>& batch, double lr);
  // Rayleigh–Ritz on `eval` (e.g. ≥ 400k points or a lattice); folds it into Ψ when `fold`.
  RitzResult readout(const std::vector<SurfacePoint>& eval, bool fold = true);
  // Ψ at points, N × K.
  std::vector<float> evaluate(const std::vector<Eigen::Vector3d>& x);

  std::vector<float> params_host() const;
  const field::Mlp& mlp() const { return mlp_; }
  const SpectralTrainConfig& config() const { return cfg_; }
  double lr_at(int step) const;

 private:
  cl::Runtime& rt_;
  SpectralTrainConfig cfg_;
  field::Mlp mlp_;
  cl::Buffer params_, grad_;
  field::Adam adam_;
  SpectralObjective objective_;
  Rng rng_;
};

}  // namespace sgnlf::spectral
