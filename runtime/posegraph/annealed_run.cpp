// run_annealed (see annealed_run.hpp).
#include "posegraph/annealed_run.hpp"

#include <cmath>
#include <string>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::posegraph {

void AnnealConfig::validate() const {
  check_range("annealed run", "steps", steps, 1, 1 << 24);
  check_range("annealed run", "per_call", per_call, 1, 1 << 24);
  check_range("annealed run", "lr_final", lr_final, 1e-6, 1.0);
  check_range("annealed run", "lr_start", lr_start, 1e-6, 1.0);
}

std::vector<GeometricResult> run_annealed(
    std::shared_ptr<const GraphLoss> loss, const GeometricConfig& base, const AnnealConfig& a,
    std::vector<Pose>& T, const std::function<void(int, double, const GeometricResult&)>& on_call) {
  require(loss != nullptr, "run_annealed: null loss");
  const size_t frames = loss->frames();
  return run_annealed(GraphLoss::as_pose_loss(std::move(loss)), frames, base, a, T, on_call);
}

std::vector<GeometricResult> run_annealed(
    PoseLoss loss, size_t frames, const GeometricConfig& base, const AnnealConfig& a,
    std::vector<Pose>& T, const std::function<void(int, double, const GeometricResult&)>& on_call) {
  a.validate();
  const int calls = (a.steps + a.per_call - 1) / a.per_call;
  std::vector<GeometricResult> out;
  for (int k = 1; k <= calls; ++k) {
    GeometricConfig c = base;
    c.steps = std::min(a.per_call, a.steps - (k - 1) * a.per_call);
    const double decay = a.lr_start * std::pow(a.lr_final / a.lr_start, double(k - 1) / calls);
    c.lr_rotation *= decay;
    c.lr_translation *= decay;
    const GeometricOptimizer opt(loss, frames, c);
    const double clock = a.hold_clock ? 1.0 : double(k) / calls;
    out.push_back(opt.run(T, clock));
    if (on_call) on_call(k, clock, out.back());
  }
  return out;
}

}  // namespace sgnlf::posegraph
