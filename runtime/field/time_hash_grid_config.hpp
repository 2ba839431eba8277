// The time-sliced hash grids' configuration (time_hash_grid.hpp), host-only.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::field {

struct TimeHashGridConfig {
  int levels = 8;
  int features = 4;               // per level: 1, 2, 4 or 8
  float base_resolution = 512.0f;
  float per_level_scale = 1.8114473f;  // (32768 / 512)^(1/7): finest 32768 at 8 levels
  int log2_table_xy = 14;         // entries per level (upper bound) of each plane
  int log2_table_xz = 12;
  int log2_table_yz = 12;
  int time_slices = 8;            // T
  int chunk = 0;                  // forward points per work-item: 0 = auto (64 on CPUs, else 1)

  // The keys and ranges (core/config_fields.hpp); features' set and the finest resolution are
  // validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("levels", s.levels, 1, 32);
    v("features", s.features, 1, 8);
    v("base_resolution", s.base_resolution, 1.0f, 65536.0f);
    v("per_level_scale", s.per_level_scale, 1.0f, 4.0f);
    v("log2_table_xy", s.log2_table_xy, 4, 24);
    v("log2_table_xz", s.log2_table_xz, 4, 24);
    v("log2_table_yz", s.log2_table_yz, 4, 24);
    v("time_slices", s.time_slices, 1, 1024);
    v("chunk", s.chunk, 0, 4096);
  }
  void validate(const std::string& where = "time_hash_grid") const;  // throws ConfigError
  static TimeHashGridConfig from_json(const Json& j, const std::string& where);
  Json to_json() const;
};

}  // namespace sgnlf::field
