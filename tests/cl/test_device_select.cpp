#include <catch2/catch.hpp>

#include "cl/device.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("devices are listed with their properties", "[cl][device]") {
  const auto devs = cl::list_devices();
  REQUIRE(!devs.empty());
  for (size_t i = 0; i < devs.size(); ++i) {
    CHECK(devs[i].index == int(i));
    CHECK(!devs[i].name.empty());
    CHECK(devs[i].compute_units > 0);
    CHECK(devs[i].global_mem_bytes > 0);
    CHECK(devs[i].max_work_group_size > 0);
  }
}

TEST_CASE("device selection by index and by name substring", "[cl][device]") {
  const auto devs = cl::list_devices();
  const auto by_index = cl::select_device("0");
  CHECK(by_index.id == devs[0].id);
  // Case-insensitive substring of the device name...
  std::string part = devs[0].name.substr(0, std::min<size_t>(6, devs[0].name.size()));
  for (auto& c : part) c = char(std::toupper(static_cast<unsigned char>(c)));
  CHECK(cl::select_device(part).id == devs[0].id);
  // ... or of the platform name.
  CHECK(cl::select_device(devs[0].platform_name).platform == devs[0].platform);
}

TEST_CASE("no match gives an error that lists the devices", "[cl][device]") {
  const auto devs = cl::list_devices();
  try {
    cl::select_device("no-such-device-xyz");
    FAIL("expected DeviceError");
  } catch (const cl::DeviceError& e) {
    const std::string msg = e.what();
    CHECK_THAT(msg, Catch::Contains("no-such-device-xyz"));
    for (const auto& d : devs) CHECK_THAT(msg, Catch::Contains(d.name));
  }
  CHECK_THROWS_AS(cl::select_device(std::to_string(devs.size() + 5)), cl::DeviceError);
}
