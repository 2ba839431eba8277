#include "support/test_device.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "cl/shared_runtime.hpp"
#include "core/rng.hpp"

namespace sgnlf::test {
namespace {
bool& needs_device_flag() {
  static bool flag = false;
  return flag;
}
}  // namespace

void mark_needs_device() { needs_device_flag() = true; }
bool binary_needs_device() { return needs_device_flag(); }

cl::Runtime& runtime() { return cl::shared_runtime(); }

std::string source_dir() { return SGNLF_SOURCE_DIR; }
std::string shared_dir() {
  const char* env = std::getenv("SGNLF_SHARED_DIR");
  return env && *env ? std::string(env) : std::string(SGNLF_SHARED_DIR);
}

std::string temp_dir(const std::string& name) {
  namespace fs = std::filesystem;
  // Under this build tree (SGNLF_TEST_TMP_DIR): two checkouts, or two build folders of one
  // checkout, testing at the same time no longer share (and wipe) fixed /tmp/sgnlf-test-* folders.
  const fs::path p = fs::path(SGNLF_TEST_TMP_DIR) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p.string();
}

std::vector<float> uniform(size_t n, float lo, float hi, uint64_t seed) {
  Rng r(seed);
  std::vector<float> v(n);
  for (auto& x : v) x = r.uniform(lo, hi);
  return v;
}

}  // namespace sgnlf::test
