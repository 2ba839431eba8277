// Ψ training loop and readout (spectral_trainer.hpp).
#include "spectral/spectral_trainer.hpp"

#include <cmath>

#include "core/error.hpp"

namespace sgnlf::spectral {

SpectralTrainer::SpectralTrainer(cl::Runtime& rt, const SpectralTrainConfig& cfg)
    : rt_(rt),
      cfg_((cfg.validate(), cfg)),
      mlp_(rt, psi_mlp_spec(cfg.psi)),
      params_(rt, mlp_.n_params() * sizeof(float)),
      grad_(rt, mlp_.n_params() * sizeof(float)),
      adam_(rt, mlp_.n_params()),
      objective_(rt, mlp_, cfg.loss),
      rng_(cfg.seed, 1) {
  std::vector<float> p(mlp_.n_params(), 0.0f);
  init_psi_params(mlp_, cfg_.psi, p, 0, cfg_.seed);
  params_.write_vec(p);
  grad_.fill_zero();
}

double SpectralTrainer::lr_at(int step) const {
  const double t = cfg_.steps > 1 ? double(step) / double(cfg_.steps - 1) : 1.0;
  const double f = cfg_.lr_final + (1 - cfg_.lr_final) * 0.5 * (1 + std::cos(3.141592653589793 * t));
  return cfg_.lr * f;
}

double SpectralTrainer::step(const std::vector<SurfacePoint>& batch, double lr) {
  const auto res = objective_.loss_and_grad(params_, 0, batch, grad_, 0);
  adam_.begin_step();
  adam_.update(params_, grad_, 0, mlp_.n_params(), float(lr));
  return res.loss;
}

SpectralTrainSummary SpectralTrainer::train(const SurfaceSampler& sampler,
                                            const std::function<void(int, double)>& on_step) {
  SpectralTrainSummary s;
  for (int i = 0; i < cfg_.steps; ++i) {
    const double loss = step(sampler(rng_, size_t(cfg_.batch)), lr_at(i));
    if (!std::isfinite(loss)) throw NumericError("spectral training: loss not finite at step " + std::to_string(i));
    if (i == 0) s.first_loss = loss;
    s.final_loss = loss;
    s.loss_curve.push_back(loss);
    if (on_step) on_step(i, loss);
  }
  rt_.finish();
  s.steps = cfg_.steps;
  return s;
}

RitzResult SpectralTrainer::readout(const std::vector<SurfacePoint>& eval, bool fold) {
  const auto mom = objective_.moments(params_, 0, eval);
  auto ritz = rayleigh_ritz(mom.S(), mom.P(), mom.mean());
  if (fold) {
    auto p = params_host();
    fold_into_psi(mlp_, p, 0, ritz);
    params_.write_vec(p);
  }
  return ritz;
}

std::vector<float> SpectralTrainer::evaluate(const std::vector<Eigen::Vector3d>& x) {
  return objective_.evaluate(params_, 0, x);
}

std::vector<float> SpectralTrainer::params_host() const { return params_.read_vec<float>(mlp_.n_params()); }

}  // namespace sgnlf::spectral
