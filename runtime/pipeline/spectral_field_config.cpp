// SpectralFieldConfig (spectral_field_config.hpp).
#include "pipeline/spectral_field_config.hpp"

#include <cmath>

#include "core/error.hpp"

namespace sgnlf::pipeline {

void SpectralFieldConfig::validate(const std::string& where) const {
  const std::string w = where + ".spectral";
  psi.validate();
  loss.validate();
  fusion.validate();
  check_range(w, "every", every, 1, 1000000);
  check_range(w, "batch", batch, 16, 1 << 20);
  check_range(w, "lr", lr, 0.0, 1.0);
  check_range(w, "lr_final", lr_final, 0.0, 1.0);
  check_range(w, "points_per_frame", points_per_frame, 16, 1 << 22);
  check_range(w, "radius_m", radius_m, 1e-3, 100.0);
}

SpectralFieldConfig SpectralFieldConfig::from_json(ConfigReader& r) {
  SpectralFieldConfig c;
  if (!r.has("spectral")) return c;
  auto s = r.child("spectral");
  const std::string w = r.where() + ".spectral";
  Json sub;
  if (s.has("psi")) {
    s.get("psi", sub);
    c.psi = spectral::PsiSpec::from_json(sub, w + ".psi");
  }
  if (s.has("loss")) {
    s.get("loss", sub);
    c.loss = spectral::SpectralLossConfig::from_json(sub, w + ".loss");
  }
  if (s.has("fusion")) {
    s.get("fusion", sub);
    c.fusion = spectral::FusionRamp::from_json(sub, w + ".fusion");
  }
  s.get("enabled", c.enabled).get("every", c.every).get("batch", c.batch);
  s.get("lr", c.lr).get("lr_final", c.lr_final);
  s.get("points_per_frame", c.points_per_frame).get("radius_m", c.radius_m);
  s.finish();
  return c;
}

void SpectralFieldConfig::to_json(Json& j) const {
  j["spectral"] = Json{{"enabled", enabled},
                       {"psi", psi.to_json()},
                       {"loss", loss.to_json()},
                       {"fusion", fusion.to_json()},
                       {"every", every},
                       {"batch", batch},
                       {"lr", lr},
                       {"lr_final", lr_final},
                       {"points_per_frame", points_per_frame},
                       {"radius_m", radius_m}};
}

double SpectralFieldConfig::lr_at(long step, long iterations) const {
  const double t = iterations > 1 ? std::min(1.0, double(step) / double(iterations - 1)) : 1.0;
  return lr * (lr_final + (1.0 - lr_final) * 0.5 * (1.0 + std::cos(3.141592653589793 * t)));
}

}  // namespace sgnlf::pipeline
