// The hash grid's configuration (hash_grid.hpp), host-only: configs that carry one (LiDAR4D's
// encoder's "static_hash", the training config's "field.grid") embed it whole and read, write
// and check it through its field list (core/config_fields.hpp) without the OpenCL launcher.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::field {

struct HashGridConfig {
  int levels = 16;
  int features = 2;          // per level: 1, 2, 4 or 8
  int log2_table_size = 19;  // entries per level (upper bound)
  float base_resolution = 16.0f;
  float per_level_scale = 1.6625f;
  // true: level-partitioned, bit-reproducible backward (one work-item per level: the fast
  // path on CPUs, too little parallelism for GPUs); false: atomic compare-and-swap adds per
  // (point, level) (summation order varies; the GPU path, and the cost comparison on CPU).
  bool deterministic = true;
  // true: forward and d_x read an fp16 copy of the table (4-byte gathers at F = 2), refreshed
  // from the fp32 parameters on the first forward after params_changed(). Gradients and Adam
  // stay fp32 (fp32 master copy).
  bool half_table = false;
  // Forward/d_x scheduling: "per_point" = one work-item per (point, level) (GPU);
  // "chunked" = one work-item per (256 points, level) with a serial loop (faster on PoCL CPU);
  // "auto" = chunked on CPU devices, per_point otherwise. Results are identical.
  std::string schedule = "auto";

  // Every key (core/config_fields.hpp); the ranges are validate()'s, which also checks the
  // feature count, the schedule's name and the finest resolution.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("levels", s.levels);
    v("features", s.features);
    v("log2_table_size", s.log2_table_size);
    v("base_resolution", s.base_resolution);
    v("per_level_scale", s.per_level_scale);
    v("deterministic", s.deterministic);
    v("half_table", s.half_table);
    v("schedule", s.schedule);
  }
  // Throws ConfigError naming `where` and the key.
  void validate(const std::string& where = "hash_grid") const;
  static HashGridConfig from_json(ConfigReader& r);  // reads known keys; caller calls finish()
  // The keys present in r onto this config (the others keep their values); no validation.
  void read_keys(ConfigReader& r);
};

// LiDAR4D's static 3D hash grid with the existing HashGrid: 8 levels × 4 features, base 512,
// finest 32768, 2^19 entries per level.
HashGridConfig lidar4d_static_hash_config();

}  // namespace sgnlf::field
