// PatchDiscriminatorConfig (patch_discriminator_config.hpp).
#include "adversarial/patch_discriminator_config.hpp"

#include "core/error.hpp"

namespace sgnlf::adversarial {
namespace {
// A JSON array of integers (rejects floats, strings and nesting), naming the key in errors.
std::vector<int> int_list(const Json& v, const std::string& where, const std::string& key) {
  if (!v.is_array()) throw ConfigError(where + ": key '" + key + "' has invalid value " + v.dump() + " (expected an array of integers)");
  std::vector<int> out;
  for (const auto& e : v) {
    if (!e.is_number_integer())
      throw ConfigError(where + ": key '" + key + "' has invalid element " + e.dump() +
                        " (expected an integer)");
    out.push_back(e.get<int>());
  }
  return out;
}
}  // namespace

void PatchDiscriminatorConfig::validate(const std::string& where) const {
  check_range(where, "scales", scales, 1, 3);
  if (channels.empty() || channels.size() > 6)
    throw ConfigError(where + ": 'channels' has " + std::to_string(channels.size()) +
                      " layers, expected 1 to 6");
  if (strides.size() != channels.size())
    throw ConfigError(where + ": 'strides' has " + std::to_string(strides.size()) +
                      " entries, 'channels' has " + std::to_string(channels.size()));
  for (size_t l = 0; l < channels.size(); ++l) {
    check_range(where, "channels[" + std::to_string(l) + "]", channels[l], 1, 512);
    check_range(where, "strides[" + std::to_string(l) + "]", strides[l], 1, 2);
  }
  check_range(where, "kernel", kernel, 2, 5);
  check_range(where, "padding", padding, 0, kernel - 1);
  check_range(where, "slope", slope, 0.0f, 1.0f);
  check_range(where, "lr", lr, 0.0f, 1.0f);
  check_range(where, "beta1", beta1, 0.0f, 0.999999f);
  check_range(where, "beta2", beta2, 0.0f, 0.999999f);
  check_range(where, "eps", eps, 0.0f, 1.0f);
  check_range(where, "depth_scale_m", depth_scale_m, 1e-3f, 1e4f);
  check_range(where, "init_std", init_std, 1e-6f, 10.0f);
}

PatchDiscriminatorConfig PatchDiscriminatorConfig::from_json(const Json& section,
                                                             const std::string& where) {
  if (!section.is_object())
    throw ConfigError(where + ": expected an object, got " + section.dump());
  PatchDiscriminatorConfig c;
  ConfigReader r(section, where);
  Json list;
  if (r.has("channels")) {
    r.get("channels", list);
    c.channels = int_list(list, where, "channels");
  }
  if (r.has("strides")) {
    r.get("strides", list);
    c.strides = int_list(list, where, "strides");
  }
  r.get("scales", c.scales).get("kernel", c.kernel).get("padding", c.padding);
  r.get("slope", c.slope).get("lr", c.lr).get("beta1", c.beta1).get("beta2", c.beta2);
  r.get("eps", c.eps).get("depth_scale_m", c.depth_scale_m).get("init_std", c.init_std);
  r.get("seed", c.seed);
  r.finish();
  c.validate(where);
  return c;
}

Json PatchDiscriminatorConfig::to_json() const {
  return Json{{"scales", scales}, {"channels", channels}, {"strides", strides},
              {"kernel", kernel}, {"padding", padding},   {"slope", slope},
              {"lr", lr},         {"beta1", beta1},       {"beta2", beta2},
              {"eps", eps},       {"depth_scale_m", depth_scale_m},
              {"init_std", init_std}, {"seed", seed}};
}

}  // namespace sgnlf::adversarial
