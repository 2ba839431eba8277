#include "harness/device_baseline.hpp"

#include <cctype>
#include <filesystem>

#include "core/json_lookup.hpp"

namespace sgnlf::harness {
namespace {

namespace fs = std::filesystem;
constexpr auto at = &member_or_null;

const Json& opencl(const Json& r) { return at(at(r, "context"), "opencl"); }
const Json& profile_name(const Json& r) { return at(at(at(r, "context"), "device_profile"), "name"); }

// Lower-case letters, digits and dots; any other run of characters one '-'; at most 64.
std::string slug_part(const Json& v) {
  const std::string s = v.is_string() ? v.get<std::string>() : std::string();
  std::string out;
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) && c < 128)
      out += char(std::tolower(c));
    else if (c == '.')
      out += '.';
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && (out.back() == '-' || out.back() == '.')) out.pop_back();
  while (!out.empty() && (out.front() == '-' || out.front() == '.')) out.erase(out.begin());
  if (out.size() > 64) out.resize(64);
  return out.empty() ? std::string("unknown") : out;
}

}  // namespace

bool different_profile(const Json& a, const Json& b) {
  const Json& pa = profile_name(a);
  const Json& pb = profile_name(b);
  return !pa.is_null() && !pb.is_null() && pa != pb;
}

bool same_device(const Json& a, const Json& b) {
  const Json& ca = opencl(a);
  const Json& cb = opencl(b);
  return ca.is_object() && cb.is_object() && at(ca, "device") == at(cb, "device") &&
         at(ca, "driver_version") == at(cb, "driver_version") && !different_profile(a, b);
}

std::string device_slug(const Json& results) {
  const Json& c = opencl(results);
  std::string s = slug_part(at(c, "device")) + "_" + slug_part(at(c, "driver_version"));
  if (!profile_name(results).is_null()) s += "_" + slug_part(profile_name(results));
  return s;
}

std::string device_baseline_path(const std::string& baseline_path, const Json& fresh) {
  return (fs::path(baseline_path).parent_path() / "devices" / device_slug(fresh) / "results.json")
      .string();
}

BaselineChoice choose_baseline(const std::string& baseline_path, const Json& baseline,
                               const Json& fresh) {
  BaselineChoice c{baseline_path, baseline, false, ""};
  if (at(baseline, "scale") != Json("smoke") || same_device(fresh, baseline)) return c;
  c.looked_for = device_baseline_path(baseline_path, fresh);
  if (fs::is_regular_file(c.looked_for)) {
    c.path = c.looked_for;
    c.baseline = load_json_file(c.looked_for);
    c.per_device = true;
  }
  return c;
}

}  // namespace sgnlf::harness
