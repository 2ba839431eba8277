// PatchDiscriminatorConfig (patch_discriminator_config.hpp).
#include "adversarial/patch_discriminator_config.hpp"

#include "core/config.hpp"
#include "core/config_fields.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace sgnlf::adversarial {

void PatchDiscriminatorConfig::validate(const std::string& where) const {
  config::check_fields(*this, where);
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
  check_range(where, "padding", padding, 0, kernel - 1);
}

PatchDiscriminatorConfig PatchDiscriminatorConfig::from_json(const Json& section,
                                                             const std::string& where) {
  PatchDiscriminatorConfig c;
  ConfigReader r(section, where);  // refuses a section that is not an object
  config::read_fields_here(r, c);  // the layer lists: integers only
  r.finish();
  c.validate(where);
  return c;
}

Json PatchDiscriminatorConfig::to_json() const { return config::write_fields(*this); }

std::pair<int, int> discriminator_logit_size(const PatchDiscriminatorConfig& c, int scale, int h, int w) {
  for (int s = 0; s < scale; ++s) {
    if (h < 2 || w < 2) return {0, 0};
    h /= 2;
    w /= 2;
  }
  auto out = [&](int in, int stride) {  // conv::Conv2dSpec::out_size
    return in + 2 * c.padding < c.kernel ? 0 : (in + 2 * c.padding - c.kernel) / stride + 1;
  };
  for (size_t l = 0; l <= c.channels.size(); ++l) {
    const int stride = l < c.strides.size() ? c.strides[l] : 1;  // the logit layer: stride 1
    h = out(h, stride);
    w = out(w, stride);
    if (h < 1 || w < 1) return {0, 0};
  }
  return {h, w};
}

namespace {
bool fits(const PatchDiscriminatorConfig& c, int h, int w) {
  for (int s = 0; s < c.scales; ++s)
    if (discriminator_logit_size(c, s, h, w).first < 1) return false;
  return true;
}
}  // namespace

PatchDiscriminatorConfig fit_discriminator_to_image(const PatchDiscriminatorConfig& c, int h, int w) {
  if (fits(c, h, w)) return c;
  PatchDiscriminatorConfig f = c;
  while (f.scales > 1 && !fits(f, h, w)) --f.scales;
  for (size_t l = 0; l < f.strides.size() && !fits(f, h, w); ++l) f.strides[l] = 1;
  const std::string image = std::to_string(h) + " × " + std::to_string(w);
  if (!fits(f, h, w))
    throw ConfigError("discriminator: no layer stack of kernel " + std::to_string(c.kernel) + ", padding " +
                      std::to_string(c.padding) + " and " + std::to_string(c.channels.size() + 1) +
                      " layers leaves logits on a " + image + " image, even at one scale and stride 1");
  std::string strides;
  for (int s : f.strides) strides += (strides.empty() ? "" : ", ") + std::to_string(s);
  log::info("discriminator: fitted to the ", image, " image: ", f.scales, " scale(s) (of ", c.scales,
            "), strides [", strides, "]");
  return f;
}

}  // namespace sgnlf::adversarial
