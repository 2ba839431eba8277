// The fusion ramp λ(t) (fusion_ramp.hpp).
#include "spectral/fusion_ramp.hpp"

#include "core/error.hpp"

namespace sgnlf::spectral {

double FusionRamp::lambda(int iteration) const {
  if (iteration >= end) return 1.0;
  if (iteration <= start) return 0.0;
  return double(iteration - start) / double(end - start);
}

void FusionRamp::validate() const {
  check_range("spectral fusion", "start", start, 0, 100000000);
  check_range("spectral fusion", "end", end, start, 100000000);
}

FusionRamp FusionRamp::from_json(const Json& j, const std::string& where) {
  FusionRamp f;
  ConfigReader r(j, where);
  r.get("start", f.start).get("end", f.end);
  r.finish();
  f.validate();
  return f;
}

Json FusionRamp::to_json() const { return Json{{"start", start}, {"end", end}}; }

}  // namespace sgnlf::spectral
