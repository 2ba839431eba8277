// Adam's settings (adam.hpp), host-only: configs that carry them (the training config's
// "optim.adam") read and check them without the OpenCL launcher.
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::field {

// The moments' settings; the learning rate is each update()'s. Embedded whole where it is
// configured (the training config's "optim.adam").
struct AdamConfig {
  float beta1 = 0.9f;
  float beta2 = 0.99f;
  float eps = 1e-15f;
  float weight_decay = 0.0f;  // L2 term added to the gradient
  // The keys and ranges (core/config_fields.hpp).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("beta1", s.beta1, 0.0f, 0.999999f);
    v("beta2", s.beta2, 0.0f, 0.999999f);
    v("eps", s.eps, 0.0f, 1.0f);
    v("weight_decay", s.weight_decay, 0.0f, 1.0f);
  }
  // Throws ConfigError naming `where` and the key.
  void validate(const std::string& where = "adam") const;
  static AdamConfig from_json(ConfigReader& r);  // caller calls finish()
};

}  // namespace sgnlf::field
