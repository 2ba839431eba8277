#include "support/real_data.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include "support/test_device.hpp"

namespace sgnlf::test {
namespace fs = std::filesystem;

namespace {
bool env_is(const char* name, const std::string& value) {
  const char* v = std::getenv(name);
  return v && value == v;
}

std::string missing_message(const std::string& path) {
  return "real data not found: " + path +
         " (set SGNLF_SHARED_DIR to the folder holding data/real; CI=true or "
         "SGNLF_REQUIRE_REAL_DATA=1 make it required)";
}
}  // namespace

bool real_data_required() { return env_is("CI", "true") || env_is("SGNLF_REQUIRE_REAL_DATA", "1"); }
std::string real_data_root() { return shared_dir() + "/data/real"; }
std::string real_sample_root() { return source_dir() + "/datasets/real-sample"; }

RealData real_data(const std::string& name) {
  const std::string full = real_data_root() + "/" + name;
  if (fs::exists(full)) return {full, true};
  if (real_data_required()) FAIL(missing_message(full));
  const std::string sample = real_sample_root() + "/" + name;
  if (fs::exists(sample)) {
    WARN(missing_message(full) + "; using the in-repo sample " + sample);
    return {sample, false};
  }
  WARN(missing_message(full) + "; the in-repo sample lacks it too (" + sample + "); skipped");
  return {};
}

RealData full_real_data(const std::string& name, const std::string& needs) {
  const std::string full = real_data_root() + "/" + name;
  if (fs::exists(full)) return {full, true};
  if (real_data_required()) FAIL(missing_message(full));
  WARN(missing_message(full) + "; skipped: this test needs " + needs);
  return {};
}

}  // namespace sgnlf::test
