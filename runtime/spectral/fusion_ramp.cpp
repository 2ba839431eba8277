// The fusion ramp λ(t) (fusion_ramp.hpp).
#include "core/config_fields.hpp"
#include "spectral/fusion_ramp.hpp"

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::spectral {

double FusionRamp::lambda(int iteration) const {
  if (iteration >= end) return 1.0;
  if (iteration <= start) return 0.0;
  return double(iteration - start) / double(end - start);
}

void FusionRamp::validate() const {
  config::check_fields(*this, "spectral fusion");
  check_range("spectral fusion", "end", end, start, 100000000);
}

FusionRamp FusionRamp::from_json(const Json& j, const std::string& where) {
  FusionRamp f;
  ConfigReader r(j, where);
  config::read_fields_here(r, f);
  r.finish();
  f.validate();
  return f;
}

Json FusionRamp::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::spectral
