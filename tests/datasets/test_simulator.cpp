// The synthetic generator: physical checks (flat ground ranges and intensities per beam),
// determinism, the ray-drop band, the on-disk round trip and the loop sequence.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"
#include "datasets/sim_lidar.hpp"
#include "datasets/simulate.hpp"
#include "io/scan_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

TEST_CASE("flat ground at a known height: exact range and intensity per beam", "[sim]") {
  sim::Scene scene;
  scene.ground_z = -0.5f;
  scene.ground_reflectance = 0.4f;
  scene.ground_texture = 0.f;
  scene.build();
  Sensor s = sensor_preset("kitti360");
  s.width = 128;
  sim::LidarModel m;
  m.noise = false;
  m.beams = "grid";
  m.ego_vehicle = false;
  Pose T = Pose::Identity();
  T.translation() = Vec3(3, -2, 1.23);  // sensor 1.73 m above the ground
  sim::DropStats st;
  const auto pts = sim::cast_scan(scene, s, T, m, 1, 0, 2, &st);
  const RangeImage img = project_points(s, pts);
  CHECK(st.rays == size_t(s.height) * s.width);
  CHECK(pts.size() == st.returns);
  size_t checked = 0;
  for (int r = 0; r < s.height; ++r) {
    const double elev = (s.fov_up_deg - r * s.fov_deg / s.height) * M_PI / 180.0;
    const double expect = elev < 0 ? 1.73 / std::sin(-elev) : 0.0;
    const double cos_i = elev < 0 ? std::sin(-elev) : 0.0;
    const bool returns = elev < 0 && expect < 80.0 && cos_i >= m.grazing_cos &&
                         0.4 * cos_i * 100.0 / (expect * expect) >= m.weak_power;
    for (int c = 0; c < s.width; ++c) {
      const size_t i = img.idx(r, c);
      if (!returns) {
        REQUIRE(img.range[i] == 0.f);
        continue;
      }
      REQUIRE(img.range[i] == Approx(expect).epsilon(2e-5));
      REQUIRE(img.intensity[i] == Approx(0.4 * (0.7 + 0.3 * cos_i) * std::exp(-expect / 250.0)).epsilon(1e-4));
      ++checked;
    }
  }
  CHECK(checked > size_t(50) * s.width);  // rows below about −2.4° return
}

TEST_CASE("simulate: same seed bit-identical (any thread count), other seed different", "[sim]") {
  SimOptions o;
  o.sequence = "kitti360-low-b";
  o.frames = 2;
  o.width = 256;
  o.lidar.beams = "grid";
  o.threads = 1;
  const auto a = simulate(o);
  o.threads = 2;
  const auto b = simulate(o);
  o.seed = 2;
  const auto c = simulate(o);
  REQUIRE(a.dataset.frames.size() == 2);
  for (size_t k = 0; k < 2; ++k) {
    const auto& pa = a.dataset.frames[k].points;
    const auto& pb = b.dataset.frames[k].points;
    REQUIRE(pa.size() == pb.size());
    CHECK(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(PointXYZI)) == 0);
    CHECK(a.dataset.frames[k].T_world_lidar.matrix() == b.dataset.frames[k].T_world_lidar.matrix());
  }
  const auto& pc = c.dataset.frames[0].points;
  const auto& pa = a.dataset.frames[0].points;
  CHECK((pc.size() != pa.size() || std::memcmp(pc.data(), pa.data(), pa.size() * sizeof(PointXYZI)) != 0));
  CHECK(a.metadata.dump() == b.metadata.dump());
  // The native HDL-64E pattern too.
  SimOptions n;
  n.sequence = "kitti360-dynamic";
  n.frames = 1;
  n.threads = 1;
  const auto n1 = simulate(n);
  n.threads = 2;
  const auto n2 = simulate(n);
  const auto& q1 = n1.dataset.frames[0].points;
  REQUIRE(q1.size() == n2.dataset.frames[0].points.size());
  CHECK(q1.size() > 100000);
  CHECK(std::memcmp(q1.data(), n2.dataset.frames[0].points.data(), q1.size() * sizeof(PointXYZI)) == 0);
}

TEST_CASE("simulated returns land in their own pixel; range image drop rate in a realistic band", "[sim]") {
  // One ray per pixel: projection keeps every return (protocol §1 round trip).
  SimOptions g;
  g.sequence = "kitti360-1538";
  g.frames = 1;
  g.lidar.beams = "grid";
  const auto rg = simulate(g);
  ProjectionStats ps;
  project_points(rg.dataset.sensor, rg.dataset.frames[0].points, &ps);
  CHECK(ps.projected == rg.dataset.frames[0].points.size());
  CHECK(ps.occluded == 0);
  // Native beams (HDL-64E / HDL-32E): full named sequences measure range-image drop rates of
  // 0.17-0.20 (KITTI-like) and 0.17-0.21 (nuScenes-like); the real KITTI slice has 0.28, the
  // real nuScenes frame 0.29. The lead's realistic band is 0.10-0.30.
  for (const char* seq : {"kitti360-low-c", "nuscenes-low-a"}) {
    SimOptions o;
    o.sequence = seq;
    o.frames = 3;
    const auto r = simulate(o);
    const double drop = r.metadata["ray_drop"]["image_drop_rate"].get<double>();
    INFO(seq << " image drop rate " << drop);
    CHECK(drop > 0.10);
    CHECK(drop < 0.30);
    CHECK(r.metadata["ray_drop"]["no_hit"].get<double>() > 0);
    CHECK(r.metadata["ray_drop"]["random"].get<double>() > 0);
  }
}

TEST_CASE("synthetic layout on disk: loads through the KITTI-360 path, byte-identical rewrite", "[sim]") {
  SimOptions o;
  o.sequence = "kitti360-low-d";
  o.frames = 6;
  o.width = 200;
  o.height = 32;
  o.lidar.beams = "grid";
  const auto r = simulate(o);
  const std::string dir = test::temp_dir("sim_disk"), dir2 = test::temp_dir("sim_disk2");
  write_synthetic(r, dir);
  write_synthetic(simulate(o), dir2);
  CHECK(detect_layout(dir) == "synthetic");
  const Dataset d = load_dataset(dir);
  CHECK(d.source == "synthetic");
  CHECK(d.frequency == "low");
  CHECK(d.sensor.width == 200);
  REQUIRE(d.frames.size() == 6);
  CHECK(d.frames[1].id == 5);  // every 5th native frame
  CHECK(d.split.test == std::vector<int>{4});
  for (size_t k = 0; k < 6; ++k) {
    CHECK((d.frames[k].T_world_lidar.matrix() - r.dataset.frames[k].T_world_lidar.matrix()).norm() < 1e-9);
    CHECK(d.frames[k].points.size() == r.dataset.frames[k].points.size());
    CHECK(d.frames[k].image.range == r.dataset.frames[k].image.range);
    CHECK(d.frames[k].timestamp_s == Approx(0.5 * k));
  }
  for (const std::string f : {"/data_poses/kitti360-low-d_sync/poses.txt", "/sgnlf_dataset.json",
                              "/data_3d_raw/kitti360-low-d_sync/velodyne_points/data/0000000025.bin"})
    CHECK(io::read_file_bytes(dir + f) == io::read_file_bytes(dir2 + f));
  // Normalisation of the training frames puts every point in [−1, 1].
  const auto n = compute_normalization(d, gt_poses(d), d.split.train);
  double mx = 0;
  for (int f : d.split.train)
    for (const auto& p : d.frames[size_t(f)].points)
      mx = std::max(mx, ((d.frames[size_t(f)].T_world_lidar * Vec3(p.x, p.y, p.z) - n.center) * n.scale).cwiseAbs().maxCoeff());
  CHECK(mx == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("loop sequence comes back to a place it passed; ego keeps moving", "[sim]") {
  SimOptions o;
  o.sequence = "kitti360-loop";
  o.width = 32;
  o.height = 4;
  o.lidar.beams = "grid";
  const auto r = simulate(o);
  const auto& f = r.dataset.frames;
  REQUIRE(f.size() == 36);
  double closest = 1e9;
  for (size_t k = 20; k < f.size(); ++k)
    closest = std::min(closest, (f[k].T_world_lidar.translation() - f[0].T_world_lidar.translation()).norm());
  CHECK(closest < 5.0);
  for (size_t k = 1; k < f.size(); ++k) {
    const double step = (f[k].T_world_lidar.translation() - f[k - 1].T_world_lidar.translation()).norm();
    CHECK(step > 4.0);  // 0.5 s at 10-12 m/s (chords of turns are shorter)
    CHECK(step < 6.05);
  }
  CHECK_THROWS_AS([] { SimOptions b; b.sequence = "nope"; simulate(b); }(), ConfigError);
}

TEST_CASE("datasets/sequences.json lists the named sequences; sensor JSON presets match", "[sim]") {
  CHECK(load_json_file(test::source_dir() + "/datasets/sequences.json") == named_sequences_json());
  for (const char* p : {"kitti360", "nuscenes"}) {
    const std::string f = test::source_dir() + "/datasets/sensors/" + p + ".json";
    CHECK(sensor_to_json(sensor_from_json(load_json_file(f), f)) == sensor_to_json(sensor_preset(p)));
  }
  int standard = 0, low = 0, loops = 0, moving = 0;
  for (const auto& s : named_sequences()) {
    standard += s.preset == "kitti360" && s.frequency == "standard" && s.frames == 64 && s.moving_vehicles == 0;
    low += s.frequency == "low" && s.frames == 36;
    loops += s.layout == "loop";
    moving += s.moving_vehicles > 0;
  }
  CHECK(standard == 4);
  CHECK(low >= 6);
  CHECK(loops >= 1);
  CHECK(moving >= 1);
}
