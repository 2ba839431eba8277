// LidarNerfModel's SG-NLF hybrid field (spectral::HybridEncoder, model.hpp): the fusion weight
// λ(t), Ψ's parameters for checkpoints, and OwnGroupStep (loss_term.hpp), through which a loss
// term gets the spectral loss's gradient of Ψ and Ψ's parameters for its own optimiser.
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

std::vector<float> LidarNerfModel::read_psi() const {
  return hybrid_or_throw("LidarNerfModel::read_psi").read_psi();
}

size_t LidarNerfModel::psi_params() const {
  return hybrid_or_throw("LidarNerfModel::psi_params").psi_params();
}

void LidarNerfModel::write_psi(const std::vector<float>& params) {
  hybrid_or_throw("LidarNerfModel::write_psi").write_psi(params);
}

double OwnGroupStep::spectral_gradient(const std::vector<spectral::SurfacePoint>& batch) {
  return model_.hybrid_or_throw("OwnGroupStep::spectral_gradient").spectral_gradient(batch);
}

OwnGroupStep::Group OwnGroupStep::psi() {
  auto& h = model_.hybrid_or_throw("OwnGroupStep::psi");
  return {h.psi_param_buffer(), h.psi_grad(), h.psi_params()};
}

}  // namespace sgnlf::pipeline
