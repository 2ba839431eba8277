// LidarNerfModel's SG-NLF hybrid field (spectral::HybridEncoder, model.hpp): the fusion weight
// λ(t), Ψ's checkpoint state, and OwnGroupStep (loss_term.hpp), through which a loss term takes
// Ψ's own optimiser step on the spectral loss.
#include <string>

#include "core/error.hpp"
#include "pipeline/model/model.hpp"
#include "spectral/hybrid_encoder.hpp"

namespace sgnlf::pipeline {

spectral::HybridEncoder& LidarNerfModel::hybrid_or_throw(const char* who) const {
  if (!hybrid_)
    throw Error(std::string(who) + ": the model has no hybrid spectral-geometric encoder "
                                   "(the config's 'spectral' section)");
  return *hybrid_;
}

void LidarNerfModel::set_fusion_weight(float lambda) {
  hybrid_or_throw("LidarNerfModel::set_fusion_weight").set_lambda(lambda);
}

float LidarNerfModel::fusion_weight() const {
  return hybrid_or_throw("LidarNerfModel::fusion_weight").lambda();
}

PsiState LidarNerfModel::psi_state() const {
  auto s = hybrid_or_throw("LidarNerfModel::psi_state").psi_state();
  return {std::move(s.params), std::move(s.adam_m), std::move(s.adam_v), s.adam_step};
}

size_t LidarNerfModel::psi_params() const {
  return hybrid_or_throw("LidarNerfModel::psi_params").psi_params();
}

void LidarNerfModel::set_psi_state(const PsiState& s) {
  hybrid_or_throw("LidarNerfModel::set_psi_state")
      .set_psi_state({s.params, s.adam_m, s.adam_v, s.adam_step});
}

double OwnGroupStep::spectral_step(const std::vector<spectral::SurfacePoint>& batch, float lr) {
  return model_.hybrid_or_throw("OwnGroupStep::spectral_step").spectral_step(batch, lr);
}

}  // namespace sgnlf::pipeline
