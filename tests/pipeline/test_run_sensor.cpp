// The run folder's record of an estimated sensor (pipeline/run/run_dir.hpp): written only for
// a sensor estimated from plain scans, and named by the load options eval, render and a resumed
// train use unless the options name a sensor themselves.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/config.hpp"
#include "pipeline/run/run_dir.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;
namespace fs = std::filesystem;

TEST_CASE("run folders keep an estimated sensor for eval, render and resume", "[pipeline][run-sensor]") {
  const std::string run = test::temp_dir("run_sensor");
  Sensor s = sensor_preset("kitti360");
  pipeline::write_run_sensor(run, s);  // a preset is found again from the data: not written
  CHECK_FALSE(fs::exists(pipeline::run_sensor_path(run)));
  LoadOptions o;
  CHECK(pipeline::run_load_options(run, o).sensor.empty());

  s.name = "estimated";
  s.height = 16, s.width = 900, s.fov_up_deg = 15.0, s.fov_deg = 32.0, s.rate_hz = 2.0;
  pipeline::write_run_sensor(run, s);
  REQUIRE(fs::exists(pipeline::run_sensor_path(run)));
  const LoadOptions lo = pipeline::run_load_options(run, o);
  CHECK(lo.sensor == pipeline::run_sensor_path(run));
  const Sensor back = sensor_from_json(load_json_file(lo.sensor), lo.sensor);
  CHECK(back.name == "estimated");
  CHECK(back.height == 16);
  CHECK(back.width == 900);
  CHECK(back.rate_hz == 2.0);

  o.sensor = "nuscenes";  // options that name a sensor keep it
  CHECK(pipeline::run_load_options(run, o).sensor == "nuscenes");
}
