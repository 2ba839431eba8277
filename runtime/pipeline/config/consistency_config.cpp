// ConsistencyConfig (consistency_config.hpp).
#include "pipeline/config/consistency_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

#include <cstdlib>

namespace sgnlf::pipeline {
namespace {

const std::string kWhere = "config.consistency";

void check_width(const Sensor& s, const std::string& what) {
  if (s.width < kMinBoundaryWidth)
    throw ConfigError(kWhere + ": the " + what + " is " + std::to_string(s.height) + " × " +
                      std::to_string(s.width) + " pixels, narrower than the reprojection's " +
                      std::to_string(kMinBoundaryWidth) + " columns");
}

}  // namespace

void ConsistencyConfig::validate(const std::string& where) const {
  const std::string w = where + ".consistency";
  config::check_fields(*this, w);
  if (offsets.empty()) throw ConfigError(w + ": 'offsets' is empty (expected e.g. [1])");
  for (size_t k = 0; k < offsets.size(); ++k)
    check_range(w, "offsets[" + std::to_string(k) + "]", offsets[k], 1, 1000);
  discriminator.validate(w + ".discriminator");
}

ConsistencyConfig ConsistencyConfig::from_json(ConfigReader& r) {
  ConsistencyConfig c;
  ConfigReader s = r.child("consistency");
  config::refuse_enabled_key(s, "consistency");
  config::read_fields_here(s, c);
  s.finish();
  return c;
}

void ConsistencyConfig::to_json(Json& j) const { j["consistency"] = config::write_fields(*this); }

Sensor consistency_render_sensor(const ConsistencyConfig& c, const Sensor& s) {
  Sensor r = s;
  r.name = s.name + "-render-" + std::to_string(c.render_rows) + "x" + std::to_string(c.render_cols);
  r.height = c.render_rows;
  r.width = c.render_cols;
  r.validate();
  check_width(r, "render sub-sensor (render_rows × render_cols)");
  return r;
}

int fitted_stride(int size, int stride) {
  if (stride <= 0 || size <= 0 || size % stride == 0) return stride;
  int best = 1;
  for (int d = 1; d <= size; ++d) {
    if (size % d != 0) continue;
    const int gap = std::abs(d - stride), best_gap = std::abs(best - stride);
    if (gap < best_gap || (gap == best_gap && d > best)) best = d;
  }
  return best;
}

ConsistencyConfig fit_consistency_to_sensor(const ConsistencyConfig& c, const Sensor& s) {
  if (c.image_row_stride > s.height)
    throw ConfigError(kWhere + ": 'image_row_stride' = " + std::to_string(c.image_row_stride) +
                      " exceeds the sensor's " + std::to_string(s.height) + " rows");
  if (c.image_col_stride > s.width)
    throw ConfigError(kWhere + ": 'image_col_stride' = " + std::to_string(c.image_col_stride) +
                      " exceeds the sensor's " + std::to_string(s.width) + " columns");
  ConsistencyConfig f = c;
  f.image_row_stride = fitted_stride(s.height, c.image_row_stride);
  f.image_col_stride = fitted_stride(s.width, c.image_col_stride);
  if (f.image_row_stride != c.image_row_stride || f.image_col_stride != c.image_col_stride)
    log::info("consistency: image strides " + std::to_string(c.image_row_stride) + " × " +
             std::to_string(c.image_col_stride) + " fitted to the " + std::to_string(s.height) +
             " × " + std::to_string(s.width) + " sensor as " +
             std::to_string(f.image_row_stride) + " × " + std::to_string(f.image_col_stride) +
             " (the nearest divisors)");
  // The discriminator runs on that image sub-sensor: its scales and strides fitted to it.
  try {
    f.discriminator = adversarial::fit_discriminator_to_image(
        c.discriminator, s.height / f.image_row_stride, s.width / f.image_col_stride);
  } catch (const ConfigError& e) {
    throw ConfigError(kWhere + ": the image sub-sensor (sensor / image strides) is too small for the " +
                      e.what() + "; smaller image strides?");
  }
  return f;
}

Sensor consistency_image_sensor(const ConsistencyConfig& config, const Sensor& s) {
  const ConsistencyConfig c = fit_consistency_to_sensor(config, s);
  Sensor r = s;
  r.height = s.height / c.image_row_stride;
  r.width = s.width / c.image_col_stride;
  r.name = s.name + "-image-" + std::to_string(r.height) + "x" + std::to_string(r.width);
  r.validate();
  check_width(r, "image sub-sensor (sensor / image strides)");
  return r;
}

}  // namespace sgnlf::pipeline
