// The K-Planes encoding's configuration (kplanes.hpp), host-only.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::field {

struct KPlanesConfig {
  int resolution = 32;       // spatial grid points per axis at the coarsest scale
  int scales = 4;            // scales 1, 2, …, 2^(scales − 1)
  int time_resolution = 8;   // grid points along t
  int features = 8;          // per plane: 1, 2, 4 or 8
  float init_lo = 0.1f;      // spatial planes start uniform in [init_lo, init_hi] (K-Planes);
  float init_hi = 0.5f;      // time planes start at 1, so the dynamic group starts static
  int chunk = 0;             // forward points per work-item: 0 = auto (64 on CPUs, else 1)

  // The keys and ranges (core/config_fields.hpp); features' set, init_lo ≤ init_hi and the
  // finest resolution are validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("resolution", s.resolution, 2, 4096);
    v("scales", s.scales, 1, 8);
    v("time_resolution", s.time_resolution, 2, 1024);
    v("features", s.features, 1, 8);
    v("init_lo", s.init_lo, -10.0f, 10.0f);
    v("init_hi", s.init_hi, -10.0f, 10.0f);
    v("chunk", s.chunk, 0, 4096);
  }
  void validate(const std::string& where = "kplanes") const;  // throws ConfigError
  static KPlanesConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::field
