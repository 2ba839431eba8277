// Configuration of SG-NLF's adversarial cross-frame consistency (method.md §4.3–4.4), the
// config's "consistency" section: when the term runs (every `every` steps after `warmup_steps`),
// its weight λ_con, which adjacent frames pair up, the sub-sampled images it works on, and the
// PatchGAN discriminator (adversarial::PatchDiscriminatorConfig, its "discriminator" object).
// Present only in the configs of methods with the term (ConfigSections::consistency, methods/), so the
// other methods' config hashes do not change; on exactly when present.
//
// Image sizes (the cost of one consistency step: results/benchmarks/consistency.md):
// frame i is rendered on a sub-sensor of render_rows × render_cols pixels with the dataset
// sensor's field of view (any size: the field renders any direction; at most the model's ray
// capacity, since one forward keeps the activations of all its rays for the backward pass);
// frame j's observed range image D_j is taken at every image_row_stride-th row and
// image_col_stride-th column (the strides must divide the sensor's height and width: then the
// sub-image is exactly the protocol's range image of a sensor with H/stride rows and W/stride
// columns, geometry/range_image.hpp's pixel_direction). D_ij is formed on that sub-sensor.
#pragma once
#include <string>
#include <vector>

#include "adversarial/patch_discriminator_config.hpp"
#include "core/config_fwd.hpp"
#include "geometry/pixel_boundaries.hpp"
#include "geometry/sensor.hpp"

namespace sgnlf::pipeline {

struct ConsistencyConfig {
  long every = 4;            // one consistency step every `every` training steps …
  long warmup_steps = 10000;  // … from this step on (method.md §4.3: after a warm-up)
  double weight = 0.05;      // λ_con (method.md §4.4); not published: chosen by the sweep
  // Partners of the step's frame i: j = i ± offset (dataset frame indices), both trainable
  // (in scene.train and not pose-only); one is drawn per step from (seed, step).
  std::vector<int> offsets{1};
  int render_rows = 16, render_cols = 64;            // frame i's render sub-sensor
  int image_row_stride = 2, image_col_stride = 10;  // frame j's image (D_j, D_ij, M_ij)
  // Rendered depths whose predicted return probability is ≤ this are set to 0 (no point:
  // the pixel is predicted as a drop), as the evaluation's masked prediction does.
  double return_threshold = 0.5;
  adversarial::PatchDiscriminatorConfig discriminator;

  // The keys and ranges (core/config_fields.hpp); offsets' entries are checked by validate().
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("every", s.every, 1L, 100000000L);
    v("warmup_steps", s.warmup_steps, 0L, 100000000L);
    v("weight", s.weight, 0.0, 1e6);
    v("offsets", s.offsets);
    v("render_rows", s.render_rows, 1, 4096);
    v("render_cols", s.render_cols, kMinBoundaryWidth, 65536);
    v("image_row_stride", s.image_row_stride, 1, 4096);
    v("image_col_stride", s.image_col_stride, 1, 65536);
    v("return_threshold", s.return_threshold, 0.0, 1.0);
    v.object("discriminator", s.discriminator);
  }
  void validate(const std::string& where) const;  // where + ".consistency" in errors
  static ConsistencyConfig from_json(ConfigReader& r);  // reads "consistency"
  void to_json(Json& j) const;                         // adds the "consistency" section
  bool active_at(long step) const {
    return step >= warmup_steps && (step - warmup_steps) % every == 0;
  }
};

// The divisor of `size` nearest to `stride` (ties: the larger one); `stride` when it divides.
int fitted_stride(int size, int stride);
// `c` with its image strides fitted to the sensor (fitted_stride, logged when they change) and
// its discriminator fitted to the image sub-sensor they give (adversarial::
// fit_discriminator_to_image: a 16-beam head's 16 rows take one scale), so that every preset
// runs on any sensor a folder of scans yields (e.g. 2004 columns: stride 10 becomes 12).
// Throws ConfigError naming the key when a stride exceeds the sensor's size, or the image
// sub-sensor when no discriminator fits it.
ConsistencyConfig fit_consistency_to_sensor(const ConsistencyConfig& c, const Sensor& s);
// Frame i's render sub-sensor and frame j's image sub-sensor (with the fitted strides) for a
// dataset sensor; both throw when the sub-sensor is narrower than the reprojection's minimum
// width.
Sensor consistency_render_sensor(const ConsistencyConfig& c, const Sensor& s);
Sensor consistency_image_sensor(const ConsistencyConfig& c, const Sensor& s);

}  // namespace sgnlf::pipeline
