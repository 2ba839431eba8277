// Sensor estimation for plain folders of scans (datasets/sensor_estimate.hpp) on simulated
// scans of both presets, with and without a ring field, the refusals (a 120° sector, a forced
// wrong field of view) and the loader's use of it; the --sensor / --frequency parsing.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/config.hpp"
#include "datasets/load_args.hpp"
#include "datasets/loader.hpp"
#include "datasets/loader_internal.hpp"
#include "datasets/sensor_estimate.hpp"
#include "datasets/simulate.hpp"
#include "io/cloud_writers.hpp"
#include "io/scan_io.hpp"
#include "support/real_data.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

namespace {

double elev_deg(const PointXYZI& p) {
  return std::atan2(double(p.z), std::sqrt(double(p.x) * p.x + double(p.y) * p.y)) * 180.0 / M_PI;
}

// Two simulated frames of a street (2 scans are enough for every estimate).
Dataset street_scans(const std::string& preset, const std::string& beams, const std::string& sensor_json = "") {
  SimOptions o;
  o.sequence = preset == "nuscenes" ? "nuscenes-low-a" : "kitti360-low-a";
  o.frames = 2;
  o.lidar.beams = beams;
  o.sensor_json = sensor_json;
  return simulate_dataset(o);
}

std::vector<ScanSample> samples(const Dataset& d) {
  std::vector<ScanSample> s;
  for (const auto& f : d.frames) s.push_back({f.points, {}});
  return s;
}

// The ring of each point: the nearest laser elevation of the pattern.
std::vector<int32_t> rings(const std::vector<PointXYZI>& pts, const std::vector<double>& elevations) {
  std::vector<int32_t> r;
  for (const auto& p : pts) {
    const double e = elev_deg(p);
    int32_t best = 0;
    for (size_t k = 1; k < elevations.size(); ++k)
      if (std::abs(elevations[k] - e) < std::abs(elevations[size_t(best)] - e)) best = int32_t(k);
    r.push_back(best);
  }
  return r;
}

std::string write_folder(const Dataset& d, const std::string& name, const std::string& ext) {
  const std::string dir = test::temp_dir(name);
  for (size_t k = 0; k < d.frames.size(); ++k) {
    char n[32];
    std::snprintf(n, sizeof n, "/%06zu", k);
    const std::string f = dir + n + ext;
    if (ext == ".bin") io::write_kitti_bin(f, d.frames[k].points);
    else if (ext == ".pcd") io::write_pcd(f, d.frames[k].points);
    else io::write_ply(f, d.frames[k].points);
  }
  return dir;
}

}  // namespace

TEST_CASE("sensor estimate recovers the presets' range-image grid", "[datasets][sensor-estimate]") {
  for (const std::string name : {"kitti360", "nuscenes"}) {
    INFO(name);
    const Sensor p = sensor_preset(name);
    const SensorEstimate e = estimate_sensor(samples(street_scans(name, "grid")));
    CHECK_FALSE(e.from_rings);
    CHECK(e.sensor.name == "estimated");
    CHECK(e.sensor.height == p.height);
    CHECK(e.sensor.fov_up_deg == Approx(p.fov_up_deg).margin(0.02));
    CHECK(e.sensor.fov_deg == Approx(p.fov_deg).margin(0.05));
    CHECK(std::abs(e.sensor.width - p.width) <= 1);
    CHECK(e.sensor.max_range_m > 40.0);
    CHECK(e.sensor.max_range_m <= 1.1 * p.max_range_m + 1.0);
    CHECK(e.azimuth_coverage_deg >= 355.0);
    CHECK(e.kept_fraction >= 0.999);
    CHECK(matching_preset(e.sensor) == name);
  }
}

TEST_CASE("sensor estimate finds the native lasers of the HDL-64E and HDL-32E", "[datasets][sensor-estimate]") {
  struct Case { std::string name; int rows; double top, bottom; int width; };
  for (const Case& c : {Case{"kitti360", 64, 2.0, -24.33, 2083}, Case{"nuscenes", 32, 10.67, -30.67, 1084}}) {
    INFO(c.name);
    const SensorEstimate e = estimate_sensor(samples(street_scans(c.name, "native")));
    std::string beams;
    for (double x : e.beam_elevation_deg) beams += std::to_string(x).substr(0, 6) + " ";
    INFO("beams " << beams);
    CHECK(e.sensor.height == c.rows);
    CHECK(e.beam_elevation_deg.front() == Approx(c.top).margin(0.02));
    CHECK(e.beam_elevation_deg.back() == Approx(c.bottom).margin(0.02));
    CHECK(e.sensor.fov_deg == Approx((c.top - c.bottom) * c.rows / (c.rows - 1)).margin(0.05));
    CHECK(std::abs(e.sensor.width - c.width) <= c.width / 100);
    CHECK(matching_preset(e.sensor) == c.name);  // the presets' images are half the native columns
  }
}

TEST_CASE("sensor estimate takes the beam count from the ring field", "[datasets][sensor-estimate]") {
  const Dataset d = street_scans("nuscenes", "native");
  std::vector<double> elev;
  for (int k = 0; k < 32; ++k) elev.push_back(10.67 - k * 4.0 / 3.0);
  const std::string dir = test::temp_dir("sensor_rings");
  std::vector<std::string> files;
  for (size_t k = 0; k < d.frames.size(); ++k) {
    // Ring 5 returns nothing: the elevation histogram shows 31 beams, the ring field still 32.
    io::ScanExtras ex;
    std::vector<PointXYZI> pts;
    const auto r = rings(d.frames[k].points, elev);
    for (size_t i = 0; i < r.size(); ++i)
      if (r[i] != 5) pts.push_back(d.frames[k].points[i]), ex.ring.push_back(r[i]);
    ex.has_ring = true;
    files.push_back(dir + "/" + std::to_string(k) + ".pcd");
    io::write_pcd(files.back(), pts, io::PcdEncoding::kBinary, &ex);
  }
  const auto sample = read_scan_sample(files);
  REQUIRE(sample.size() == 2);
  REQUIRE(sample[0].ring.size() == sample[0].points.size());
  const SensorEstimate e = estimate_sensor(sample);
  CHECK(e.from_rings);
  CHECK(e.sensor.height == 32);
  CHECK(e.sensor.fov_up_deg == Approx(10.67).margin(0.02));
  CHECK(std::abs(e.sensor.width - 1084) <= 10);
  // Without the ring field the same points show 31 peaks.
  std::vector<ScanSample> no_ring = sample;
  for (auto& s : no_ring) s.ring.clear();
  CHECK(estimate_sensor(no_ring).sensor.height == 31);
}

TEST_CASE("the preset match survives merged beams; other heads match nothing", "[datasets][sensor-estimate]") {
  auto est = [](int rows, int width, double fov_up, double fov) {
    Sensor s;
    s.name = "estimated";
    s.height = rows, s.width = width, s.fov_up_deg = fov_up, s.fov_deg = fov;
    return s;
  };
  // A 21-scan folder of KITTI odometry HDL-64E scans: three beams merged (61 rows) and a
  // measured width of 2 004 (no preset matched, and the quick preset's training stopped on it).
  CHECK(matching_preset(est(61, 2004, 2.86, 27.4)) == "kitti360");
  // The spread of one HDL-64E on subsets of the ten KITTI scans of ../shared: 59 to 69 rows,
  // fov_up 3.1 to 3.9°, fov 27.8 to 28.6°.
  CHECK(matching_preset(est(59, 2005, 3.81, 28.43)) == "kitti360");
  CHECK(matching_preset(est(62, 2003, 3.92, 28.52)) == "kitti360");
  CHECK(matching_preset(est(69, 2005, 3.92, 28.47)) == "kitti360");
  // The HDL-32E with a beam missing (31 peaks) or an extra one.
  CHECK(matching_preset(est(31, 1084, 10.67, 42.7)) == "nuscenes");
  CHECK(matching_preset(est(33, 1084, 10.67, 42.7)) == "nuscenes");
  // Heads of other beam counts or fields of view are none of the presets.
  CHECK(matching_preset(est(57, 2005, 3.0, 27.0)).empty());   // more than 1/8 below 66
  CHECK(matching_preset(est(128, 2048, 2.0, 26.9)).empty());  // a 128-beam head
  CHECK(matching_preset(est(40, 1800, 7.0, 23.0)).empty());   // a 40-beam head (+7° to −16°)
  CHECK(matching_preset(est(64, 1024, 22.5, 45.0)).empty());  // a 64-beam head of ±22.5°
  CHECK(matching_preset(est(64, 2048, 5.0, 26.9)).empty());   // the top beam 3° off
  CHECK(matching_preset(est(16, 900, 15.0, 32.0)).empty());   // VLP-16
  CHECK(matching_preset(est(64, 900, 2.0, 26.9)).empty());    // coarser than the preset's image
}

TEST_CASE("the estimated width is a multiple of kWidthMultiple", "[datasets][sensor-estimate]") {
  // The simulated native HDL-64E: 2 083 azimuth steps, estimated as 2 080 columns.
  const SensorEstimate e = estimate_sensor(samples(street_scans("kitti360", "native")));
  CHECK(e.sensor.width % kWidthMultiple == 0);
  CHECK(std::abs(e.sensor.width - 2083) <= kWidthMultiple / 2);
  // A 2 003-column head (a prime: no image stride but 1 would divide it) is estimated at 2 000.
  const std::string sj = test::temp_dir("width_2003") + "/s.json";
  Sensor v = sensor_preset("kitti360");
  v.name = "w2003";
  v.width = 2003;
  write_json_file(sj, sensor_to_json(v));
  const SensorEstimate w = estimate_sensor(samples(street_scans("kitti360", "grid", sj)));
  CHECK(w.sensor.width == 2000);
  CHECK(w.kept_fraction >= 0.99);
}

TEST_CASE("sensor estimate refuses a sensor that does not spin 360°", "[datasets][sensor-estimate]") {
  auto s = samples(street_scans("kitti360", "grid"));
  for (auto& sc : s) {
    std::vector<PointXYZI> sector;
    for (const auto& p : sc.points)
      if (std::abs(std::atan2(p.y, p.x)) < M_PI / 3) sector.push_back(p);  // 120° ahead
    sc.points = sector;
  }
  CHECK_THROWS_WITH(estimate_sensor(s), Catch::Contains("cover 12") && Catch::Contains("360") &&
                                            Catch::Contains("give --sensor FILE"));
}

TEST_CASE("sensor estimate: a wrong field of view fails the 95 % check", "[datasets][sensor-estimate]") {
  const auto s = samples(street_scans("kitti360", "grid"));
  SensorEstimateOptions o;
  o.adjust = [](Sensor& x) { x.fov_deg *= 0.5; };  // the lower half of the beams left out
  CHECK_THROWS_WITH(estimate_sensor(s, o), Catch::Contains("failed its check") &&
                                               Catch::Contains("field-of-view") && Catch::Contains("below") &&
                                               Catch::Contains("% of the"));
  o.adjust = [](Sensor& x) { x.fov_up_deg -= 1.0; };  // the top beams cut: a smaller loss
  const auto e = [&] {
    SensorEstimateOptions lax = o;
    lax.min_kept_fraction = 0.0;
    return estimate_sensor(s, lax);
  }();
  CHECK(e.kept_fraction < 0.999);
  CHECK(e.kept_fraction > 0.5);
  CHECK_NOTHROW(estimate_sensor(s));
}

TEST_CASE("plain folders: the estimate, its matching preset, --sensor and --frequency", "[datasets][sensor-estimate]") {
  // KITTI .bin scans of the kitti360 grid: the estimate matches the preset, used as before.
  const std::string kitti = write_folder(street_scans("kitti360", "grid"), "plain_kitti", ".bin");
  CHECK(detect_layout(kitti) == "scans");
  Dataset d = load_dataset(kitti);
  CHECK(d.sensor.name == "kitti360");
  CHECK(d.sensor.rate_hz == 10.0);
  CHECK(d.frequency == "standard");

  // A 16-beam sensor no preset matches, as PLY: the estimate itself.
  const std::string sj = test::temp_dir("plain_vlp") + "/vlp16.json";
  Sensor v = sensor_preset("kitti360");
  v.name = "vlp16";
  v.height = 16, v.width = 900, v.fov_up_deg = 15.0, v.fov_deg = 32.0, v.max_range_m = 100.0;
  write_json_file(sj, sensor_to_json(v));
  const std::string vlp = write_folder(street_scans("kitti360", "grid", sj), "plain_vlp_scans", ".ply");
  d = load_dataset(vlp);
  CHECK(d.sensor.name == "estimated");
  CHECK(d.sensor.height == 16);
  CHECK(d.sensor.fov_up_deg == Approx(15.0).margin(0.02));
  CHECK(d.sensor.fov_deg == Approx(32.0).margin(0.05));
  CHECK(std::abs(d.sensor.width - 900) <= 1);
  CHECK(d.frames.at(1).timestamp_s == Approx(0.1));

  LoadOptions o;
  set_frequency_arg(o, "2");
  d = load_dataset(vlp, o);
  CHECK(d.sensor.rate_hz == 2.0);
  CHECK(d.frequency == "low");
  CHECK(d.frames.at(1).timestamp_s == Approx(0.5));
  set_sensor_arg(o, sj);
  d = load_dataset(vlp, o);
  CHECK(d.sensor.name == "vlp16");
  CHECK(d.sensor.rate_hz == 2.0);
}

TEST_CASE("--frequency and --sensor: rates, classes and refusals naming the option", "[datasets][load-args]") {
  LoadOptions o;
  set_frequency_arg(o, "2");
  CHECK(o.rate_hz == 2.0);
  CHECK(o.frequency.empty());
  CHECK(detail::resolve_frequency(o, "standard") == "low");
  CHECK(detail::default_stride(o, "low", 10.0) == 5);   // KITTI's 10 Hz to 2 Hz
  CHECK(detail::default_stride(o, "low", 20.0) == 10);  // nuScenes sweeps to 2 Hz
  set_frequency_arg(o, "10");
  CHECK(detail::resolve_frequency(o, "low") == "standard");
  CHECK(detail::default_stride(o, "standard", 10.0) == 1);
  CHECK(frequency_class(5.0) == "low");
  CHECK(frequency_class(5.01) == "standard");
  LoadOptions c;
  set_frequency_arg(c, "low");
  CHECK(c.frequency == "low");
  CHECK(c.rate_hz == 0.0);
  for (const std::string bad : {"abc", "", "0", "-2", "nan", "inf", "2Hz", "1e9"}) {
    INFO(bad);
    CHECK_THROWS_WITH(set_frequency_arg(c, bad), Catch::StartsWith("--frequency '" + bad + "'"));
  }
  CHECK(c.rate_hz == 0.0);

  set_sensor_arg(c, "nuscenes");
  CHECK(c.sensor == "nuscenes");
  CHECK_THROWS_WITH(set_sensor_arg(c, "hdl64"), Catch::StartsWith("--sensor 'hdl64'") && Catch::Contains("unknown sensor preset"));
  const std::string bad = test::temp_dir("load_args") + "/bad.json";
  write_json_file(bad, Json{{"height", 0}});
  CHECK_THROWS_WITH(set_sensor_arg(c, bad), Catch::StartsWith("--sensor '" + bad + "'") && Catch::Contains("height"));
  CHECK(c.sensor == "nuscenes");

  // The rate is a load option: validated, written to run.json and read back.
  o.rate_hz = 2.0;
  CHECK(LoadOptions::from_json(o.to_json(), "t").rate_hz == 2.0);
  o.rate_hz = -1.0;
  CHECK_THROWS_WITH(o.validate(), Catch::Contains("rate_hz"));
}

TEST_CASE("real HDL-64E scans (KITTI odometry) as a plain folder: the estimate", "[real][sensor-estimate]") {
  const test::RealData r = test::real_data("kitti-odometry-00-slice");
  if (!r) return;
  const std::string dir = r.path + "/sequences/00/velodyne";
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  const SensorEstimate e = estimate_sensor(read_scan_sample(files));
  CHECK_FALSE(e.from_rings);
  CHECK(e.sensor.height >= 60);
  CHECK(e.sensor.height <= 68);
  // Measured on the 10 scans: 65 rows, fov_up 3.23° (the real lasers stray above the nominal
  // +2°), fov 27.8°, width 2006 (the HDL-64E's ~2 083 steps less its dropped columns; estimated
  // as 2 010, a multiple of kWidthMultiple); on the in-repo sample's 2 scans: 67 rows, fov_up
  // 3.84°, fov 28.4°, width 2008.
  CHECK(e.sensor.fov_up_deg == Approx(2.0).margin(2.0));
  CHECK(e.sensor.fov_deg == Approx(26.9).margin(2.0));
  CHECK(e.sensor.width > 1800);
  CHECK(e.sensor.width < 2200);
  CHECK(e.kept_fraction >= 0.95);
  const Dataset d = load_dataset(dir);
  const std::string expected = matching_preset(e.sensor).empty() ? "estimated" : matching_preset(e.sensor);
  CHECK(d.sensor.name == expected);
  UNSCOPED_INFO("estimate " << e.sensor.height << "x" << e.sensor.width << " fov_up " << e.sensor.fov_up_deg
                            << " fov " << e.sensor.fov_deg << " -> " << d.sensor.name);
  CHECK(d.sensor.name == "kitti360");
}

TEST_CASE("real HDL-64E scans with merged beams still get the kitti360 preset", "[real][sensor-estimate]") {
  const test::RealData r = test::full_real_data("kitti-odometry-00-slice", "scans 41 to 49; the in-repo sample holds 2");
  if (!r) return;
  // Every other scan from 41: the estimate merges beams (59 rows × 2 005 measured columns,
  // fov_up 3.81°, fov 28.43°); no preset matched it before and the folder got the estimate.
  const std::string dir = test::temp_dir("kitti_odd_scans");
  for (int k = 41; k <= 49; k += 2) {
    const std::string name = "/0000" + std::to_string(k) + ".bin";
    std::filesystem::copy_file(r.path + "/sequences/00/velodyne" + name, dir + name,
                               std::filesystem::copy_options::overwrite_existing);
  }
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  const SensorEstimate e = estimate_sensor(read_scan_sample(files));
  INFO("estimate " << e.sensor.height << "x" << e.sensor.width << " fov_up " << e.sensor.fov_up_deg
                   << " fov " << e.sensor.fov_deg);
  CHECK(e.sensor.height < 62);  // merged beams: the case this test is for
  CHECK(matching_preset(e.sensor) == "kitti360");
  CHECK(load_dataset(dir).sensor.name == "kitti360");
}
