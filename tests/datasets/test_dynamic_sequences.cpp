// The dynamic twins (kitti360-dyn-*, LiDAR4D's dynamic KITTI-360 set): split, determinism,
// labels and actor boxes through the on-disk layout, actors inside a moving sweep, and the
// static sequences left exactly as they were.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <set>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/actor_truth.hpp"
#include "datasets/loader.hpp"
#include "datasets/protocol.hpp"
#include "datasets/simulate.hpp"
#include "geometry/sweep_timing.hpp"
#include "io/scan_io.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

namespace {

SimOptions small(const std::string& seq, int frames) {
  SimOptions o;
  o.sequence = seq;
  o.frames = frames;
  o.width = 360;
  o.height = 32;
  o.lidar.beams = "grid";
  o.threads = 2;
  return o;
}

// Is the world point inside actor box b (inflated by `tol` metres)?
bool inside(const ActorBox& b, const Vec3& p_world, double tol) {
  const Vec3 q = b.T_world_actor.inverse() * p_world;
  if (b.kind == "pedestrian")
    return q.head<2>().norm() <= b.half_extents.x() + tol && std::abs(q.z()) <= b.half_extents.z() + tol;
  return (q.cwiseAbs() - b.half_extents).maxCoeff() <= tol;
}

bool same_points(const std::vector<PointXYZI>& a, const std::vector<PointXYZI>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(PointXYZI)) == 0;
}

}  // namespace

TEST_CASE("LiDAR4D's dynamic split: frames 10, 20, 30, 40 of 51 are the test frames", "[sim][actors]") {
  const Split s = dynamic_split(51);
  CHECK(s.test == std::vector<int>{10, 20, 30, 40});
  CHECK(s.train.size() == 47);
  CHECK(dynamic_split(16).test == std::vector<int>{10});
  CHECK(dynamic_split(41).test == std::vector<int>{10, 20, 30});  // never the last frame
  CHECK(named_split("protocol", 64, "standard").test == protocol_split(64, "standard").test);
  CHECK_THROWS_AS(named_split("random", 10, "standard"), ConfigError);
  int dynamic = 0;
  for (const auto& n : named_sequences()) {
    if (n.name.rfind("kitti360-dyn-", 0) != 0) {
      CHECK_FALSE(n.actors.any());  // every other sequence: no actors, the protocol's split
      CHECK(n.split == "protocol");
      continue;
    }
    ++dynamic;
    CHECK(n.frames == 51);
    CHECK(n.frequency == "standard");
    CHECK(n.split == "dynamic");
    CHECK(n.actors.vehicles >= 3);
    CHECK(n.actors.crossing >= 1);
  }
  CHECK(dynamic == 6);
}

TEST_CASE("a dynamic twin: labelled actors in view, same seed same data, on disk and back", "[sim][actors]") {
  SimOptions o = small("kitti360-dyn-8120", 51);
  o.width = 720;  // 0.5° columns: a pedestrian 20 m away is 1.4° wide
  const SimResult r = simulate(o);
  const Dataset& d = r.dataset;
  REQUIRE(d.frames.size() == 51);
  CHECK(d.split.test == std::vector<int>{10, 20, 30, 40});
  REQUIRE(r.actors.size() == 3 + 6 + 2);
  std::set<int> seen;
  for (const auto& f : d.frames) {
    REQUIRE(f.labels.size() == f.points.size());
    REQUIRE(f.actors.size() == r.actors.size());
    for (size_t i = 0; i < f.points.size(); ++i) {
      if (f.labels[i] == 0) continue;
      seen.insert(f.labels[i]);
      // A labelled point lies on its actor's box at the frame's time.
      const ActorBox& b = f.actors[size_t(f.labels[i] - 1)];
      REQUIRE(b.id == f.labels[i]);
      const auto& p = f.points[i];
      REQUIRE(inside(b, f.T_world_lidar * Vec3(p.x, p.y, p.z), 0.1));
    }
  }
  INFO(seen.size() << " actors seen");
  CHECK(seen.size() >= 4);
  // The people crossing (the last ids) cross the sensor's view.
  CHECK(seen.count(int(r.actors.size())) + seen.count(int(r.actors.size()) - 1) >= 1);
  CHECK(r.metadata.at("test_frame_ids") == Json::array({10, 20, 30, 40}));

  const SimResult again = simulate(o);
  for (size_t k = 0; k < d.frames.size(); k += 7) {
    CHECK(same_points(again.dataset.frames[k].points, d.frames[k].points));
    CHECK(again.dataset.frames[k].labels == d.frames[k].labels);
  }
  SimOptions other = o;
  other.seed = 2;
  other.frames = 3;
  const SimResult r2 = simulate(other);
  CHECK((r2.actors[0].xy_ref - r.actors[0].xy_ref).norm() > 1e-3);

  const std::string dir = test::temp_dir("sim_dynamic");
  write_synthetic(r, dir);
  const Dataset back = load_dataset(dir);
  CHECK(back.split.test == std::vector<int>{10, 20, 30, 40});
  for (size_t k = 0; k < d.frames.size(); ++k) {
    REQUIRE(back.frames[k].labels == d.frames[k].labels);
    REQUIRE(back.frames[k].actors.size() == d.frames[k].actors.size());
    for (size_t a = 0; a < d.frames[k].actors.size(); ++a) {
      CHECK(back.frames[k].actors[a].kind == d.frames[k].actors[a].kind);
      CHECK((back.frames[k].actors[a].T_world_actor.matrix() - d.frames[k].actors[a].T_world_actor.matrix()).norm() < 1e-12);
    }
  }
  // A window without those frames keeps the protocol split; a label file that does not match
  // its scan is refused, naming it.
  LoadOptions w;
  w.frames = 8;
  CHECK(load_dataset(dir, w).split.test == protocol_split(8, "standard").test);
  const std::string lab = actor_labels_path(dir, 3);
  auto labels = read_labels(lab);
  labels.pop_back();
  write_labels(lab, labels);
  CHECK_THROWS_WITH(load_dataset(dir), Catch::Contains("0000000003.bin"));
}

TEST_CASE("actors move within a distorted sweep like the ego does", "[sim][actors][deskew]") {
  SimOptions o = small("kitti360-dyn-4950", 2);
  o.realism.motion_distortion = true;
  o.lidar.noise = false;  // exact ranges: the check below is to 3 cm
  const SimResult r = simulate(o);
  REQUIRE(r.sweeps.size() == 2);
  const Sensor& s = r.dataset.sensor;
  const double sweep = s.sweep_duration_s();
  size_t labelled = 0, near_frame_time = 0;
  for (size_t k = 0; k < 2; ++k) {
    const Frame& f = r.dataset.frames[k];
    const double start = f.timestamp_s + r.actor_clock_offset_s - s.sweep.reference * sweep;
    for (size_t i = 0; i < f.points.size(); ++i) {
      const uint16_t l = f.labels[i];
      if (l == 0) continue;
      ++labelled;
      const Vec3 p(f.points[i].x, f.points[i].y, f.points[i].z);
      // The point was cast at its column's time from that moment's pose, against the actor
      // placed at its slice's time (72 slices: at most half a slice, 0.7 ms, apart).
      const double fr = sweep_fraction(s.sweep, p);
      const Vec3 w = r.sweeps[k].at(fr) * p;
      const auto& a = r.actors[size_t(l - 1)];
      INFO("frame " << k << " point " << i << " actor " << l);
      REQUIRE(inside(a.box(start + fr * sweep, 0.0), w, 0.03));
      near_frame_time += inside(f.actors[size_t(l - 1)], f.T_world_lidar * p, 0.03);
    }
  }
  CHECK(labelled > 100);
  // Stored uncompensated: many actor points are off the box at the frame's one time.
  CHECK(near_frame_time < labelled);
}

TEST_CASE("static sequences: no actors, no labels, nothing new on disk", "[sim][actors]") {
  const SimResult r = simulate(small("kitti360-1538", 3));
  CHECK(r.actors.empty());
  for (const auto& f : r.dataset.frames) {
    CHECK(f.labels.empty());
    CHECK(f.actors.empty());
  }
  for (const char* key : {"actors", "split", "test_frame_ids"}) CHECK_FALSE(r.metadata.contains(key));
  CHECK_FALSE(r.metadata.at("per_frame")[0].contains("actor_returns"));
  const std::string dir = test::temp_dir("sim_static");
  write_synthetic(r, dir);
  CHECK_FALSE(std::filesystem::exists(actor_truth_path(dir)));
  CHECK_FALSE(std::filesystem::exists(std::filesystem::path(dir) / "ground_truth" / "labels"));
  CHECK(load_dataset(dir).split.test == protocol_split(3, "standard").test);
  // Actors asked for on a static street are refused when out of range, naming the key.
  SimOptions bad = small("kitti360-1538", 2);
  bad.actors.vehicles = 500;
  CHECK_THROWS_WITH(simulate(bad), Catch::Contains("'vehicles'"));
}
