// SweepTiming (see sweep_timing.hpp).
#include "geometry/sweep_timing.hpp"

#include <cmath>

#include "core/config.hpp"
#include "core/config_fields.hpp"

namespace sgnlf {

void SweepTiming::validate(const std::string& w) const {
  if (direction != -1 && direction != 1)
    throw ConfigError(w + ": 'direction' = " + std::to_string(direction) + " (expected -1 clockwise or 1 counter-clockwise)");
  config::check_fields(*this, w);
}

double sweep_fraction(const SweepTiming& t, const Vec3& p) {
  const double beta = std::atan2(p.y(), p.x());
  double f = double(t.direction) * (beta - t.start_azimuth_deg * (M_PI / 180.0)) / (2.0 * M_PI);
  f -= std::floor(f);
  return f < 1.0 ? f : 0.0;  // f − floor(f) can round up to 1 for tiny negative f
}

double sweep_time_offset(const SweepTiming& t, double duration_s, const Vec3& p) {
  return (sweep_fraction(t, p) - t.reference) * duration_s;
}

SweepTiming sweep_timing_from_json(ConfigReader& r) {
  SweepTiming t;
  config::read_fields_here(r, t);
  r.finish();
  t.validate(r.where());
  return t;
}

Json sweep_timing_to_json(const SweepTiming& t) { return config::write_fields(t); }

}  // namespace sgnlf
