// The shared Runtime of a test or benchmark binary (cl/shared_runtime.hpp): one per process
// until released, released on request (the mains do it before they return, not at exit), and
// reopened by the next use. Under Oclgrind, the label oclgrind runs this binary and fails when
// the process does not exit cleanly.
#include <catch2/catch.hpp>

#include "cl/memory.hpp"
#include "cl/shared_runtime.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("the shared runtime is one per process until released, then reopens",
          "[cl][shared]") {
  cl::Runtime& a = test::runtime();
  CHECK(&a == &cl::shared_runtime());
  CHECK(cl::shared_runtime_open());
  {
    // Objects made from it are released before the runtime is.
    auto b = cl::Buffer::from(a, std::vector<float>{1.0f, 2.0f});
    CHECK(b.read_all<float>() == std::vector<float>{1.0f, 2.0f});
  }
  cl::release_shared_runtime();
  CHECK_FALSE(cl::shared_runtime_open());
  cl::release_shared_runtime();  // a second release is a no-op
  CHECK_FALSE(cl::shared_runtime_open());
  cl::Runtime& c = test::runtime();
  CHECK(cl::shared_runtime_open());
  CHECK(c.programs_built() == 0);  // a new Runtime: its program cache starts empty
  auto b = cl::Buffer::from(c, std::vector<float>{3.0f});
  CHECK(b.read_all<float>() == std::vector<float>{3.0f});
}
