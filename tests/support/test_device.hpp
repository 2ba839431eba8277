// Shared test helpers: the test device (SGNLF_DEVICE or the default), paths to fixtures, and
// (through support/device_tolerance.hpp) the device-vs-reference comparisons.
#pragma once
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cl/runtime.hpp"
#include "support/device_tolerance.hpp"

namespace sgnlf::test {

// Marks the current binary as containing device tests (call from a static initialiser,
// see SGNLF_DEVICE_TESTS below).
void mark_needs_device();
bool binary_needs_device();

// The Runtime every device test in a binary shares: cl::shared_runtime(), released by the
// test main (catch_main.cpp) before it returns.
cl::Runtime& runtime();

std::string source_dir();
std::string shared_dir();  // $SGNLF_SHARED_DIR, else ../shared beside the checkout
// The real-data tests' paths (the large data, else the in-repo sample): support/real_data.hpp.
std::string temp_dir(const std::string& name);  // fresh empty folder under the build tree

// n values uniform in [lo, hi) from the project's generator (core/rng.hpp) seeded with `seed`.
std::vector<float> uniform(size_t n, float lo, float hi, uint64_t seed);

// The shared Runtime's device profile set to `p` for a scope (launchers read it when they are
// made, so one made inside keeps it); the previous profile comes back at the scope's end.
class ProfileScope {
 public:
  explicit ProfileScope(const cl::DeviceProfile& p) : saved_(runtime().device_profile()) {
    runtime().set_device_profile(p);
  }
  ~ProfileScope() { runtime().set_device_profile(saved_); }
  ProfileScope(const ProfileScope&) = delete;
  ProfileScope& operator=(const ProfileScope&) = delete;

 private:
  cl::DeviceProfile saved_;
};

}  // namespace sgnlf::test

// Put once in each test .cpp that uses the device.
#define SGNLF_DEVICE_TESTS \
  static const bool sgnlf_device_marker_ = (sgnlf::test::mark_needs_device(), true)
