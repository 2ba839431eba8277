// Moving actors of the simulator (runtime/datasets/sim_actors.hpp): their motion in closed form,
// the labels and ranges of the returns that hit them (against an independent analytic
// intersection), the static returns they hide, and their configuration's checks.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/config.hpp"
#include "core/error.hpp"
#include "datasets/sim_actors.hpp"
#include "datasets/sim_lidar.hpp"

using namespace sgnlf;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Reference ray–actor intersection in double, written apart from the simulator's: the box by
// slabs in its own frame, the pedestrian as a vertical cylinder (side, then top cap).
double ref_hit(const sim::ActorTrack& a, double t_s, const Vec3& o, const Vec3& d) {
  const Eigen::Vector2d c = a.position(t_s);
  if (a.kind == sim::ActorKind::vehicle) {
    const Pose T = a.pose(t_s, 0.0);
    const Vec3 lo = T.inverse() * o, ld = T.linear().transpose() * d;
    double t0 = 0, t1 = kInf;
    for (int k = 0; k < 3; ++k) {
      const double ta = (-a.half[k] - lo[k]) / ld[k], tb = (a.half[k] - lo[k]) / ld[k];
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1 ? t0 : kInf;
  }
  const double r = a.half.x(), h = 2 * a.half.z(), ox = o.x() - c.x(), oy = o.y() - c.y();
  const double A = d.x() * d.x() + d.y() * d.y(), B = ox * d.x() + oy * d.y(), C = ox * ox + oy * oy - r * r;
  double best = kInf;
  if (B * B - A * C >= 0) {
    const double t = (-B - std::sqrt(B * B - A * C)) / A, z = o.z() + t * d.z();
    if (t > 0 && z >= 0 && z <= h) best = t;
  }
  if (d.z() < 0) {
    const double t = (h - o.z()) / d.z(), x = ox + t * d.x(), y = oy + t * d.y();
    if (t > 0 && x * x + y * y <= r * r) best = std::min(best, t);
  }
  return best;
}

sim::ActorTrack car(double x, double y, double yaw) {
  sim::ActorTrack a;
  a.id = 3;
  a.xy_ref = {x, y};
  a.yaw_ref = yaw;
  a.speed = 8.0;
  a.curvature = 0.01;
  a.t_ref = 0.5;
  a.half = Vec3(2.2, 0.9, 0.75);
  return a;
}

sim::ActorTrack walker(double x, double y) {
  sim::ActorTrack a;
  a.id = 7;
  a.kind = sim::ActorKind::pedestrian;
  a.xy_ref = {x, y};
  a.yaw_ref = 1.0;
  a.speed = 1.4;
  a.curvature = -0.05;
  a.half = Vec3(0.3, 0.3, 0.9);
  return a;
}

// Every pixel of a grid scan from a sensor 1.73 m above the ground at the origin, no noise.
struct GridScan {
  Sensor s = sensor_preset("kitti360");
  sim::BeamPattern bp;
  std::vector<sim::RayReturn> px;
  Pose T = Pose::Identity();
  explicit GridScan(const sim::Scene& scene) {
    s.width = 720;
    sim::LidarModel m;
    m.noise = false;
    m.beams = "grid";
    m.ego_vehicle = false;
    bp = sim::beam_pattern(s, m.beams);
    T.translation() = Vec3(0, 0, 1.73);
    px.resize(bp.elevation_deg.size() * size_t(bp.azimuth_steps));
    std::vector<int> cols(size_t(bp.azimuth_steps));
    for (int c = 0; c < bp.azimuth_steps; ++c) cols[size_t(c)] = c;
    sim::DropStats st;
    sim::cast_columns(scene, s, bp, m, 1, 0, cols, std::vector<Pose>(cols.size(), T), 2, px, st);
  }
  Vec3 dir(size_t i) const {
    const int row = int(i / size_t(bp.azimuth_steps)), col = int(i % size_t(bp.azimuth_steps));
    return sim::beam_direction(s, bp, row, col).cast<double>().normalized();
  }
  double range(size_t i) const { return Vec3(px[i].p.x, px[i].p.y, px[i].p.z).norm(); }
};

}  // namespace

TEST_CASE("actors move at constant speed along arcs of constant curvature", "[sim][actors]") {
  const sim::ActorTrack a = car(3.0, -2.0, 0.4);
  for (double t : {-1.3, 0.0, 0.5, 0.8, 2.0, 4.75}) {
    // Closed form with sines: centre of the turn circle plus the radius vector.
    const double R = 1.0 / a.curvature, yaw = a.yaw_ref + a.curvature * a.speed * (t - a.t_ref);
    const Eigen::Vector2d expect = a.xy_ref + R * Eigen::Vector2d(std::sin(yaw) - std::sin(a.yaw_ref),
                                                                  std::cos(a.yaw_ref) - std::cos(yaw));
    INFO("t = " << t);
    CHECK((a.position(t) - expect).norm() < 1e-9);
    CHECK(a.yaw(t) == Approx(yaw));
    // The box's pose: centre on the ground + half height, x along the motion.
    const Pose T = a.pose(t, -0.2);
    CHECK(T.translation().z() == Approx(-0.2 + 0.75));
    const Eigen::Vector2d step = (a.position(t + 1e-4) - a.position(t - 1e-4)) / 2e-4;
    CHECK(step.norm() == Approx(a.speed).epsilon(1e-6));                       // constant speed
    CHECK((T.linear().col(0).head<2>() - step.normalized()).norm() < 1e-6);  // heading = motion
  }
  CHECK((a.position(a.t_ref) - a.xy_ref).norm() == 0.0);
  // A whole circle brings it back; κ = 0 is a straight line.
  CHECK((a.position(a.t_ref + 2 * M_PI / (a.curvature * a.speed)) - a.xy_ref).norm() < 1e-9);
  sim::ActorTrack b = a;
  b.curvature = 0.0;
  CHECK((b.position(a.t_ref + 2.0) - (a.xy_ref + 16.0 * Eigen::Vector2d(std::cos(0.4), std::sin(0.4)))).norm() < 1e-12);
}

TEST_CASE("returns from actors carry their id and the analytic range", "[sim][actors]") {
  sim::Scene scene;
  scene.build();
  const sim::ActorTrack a = car(11.0, 2.0, 0.3), p = walker(5.0, -4.0);
  const double t = 1.1;  // not the reference time: the car has moved and turned
  sim::place_actors(scene, {a, p}, t);
  const GridScan g(scene);
  const Vec3 o = g.T.translation();
  size_t hits[2] = {0, 0}, labelled[2] = {0, 0};
  double worst = 0;
  for (size_t i = 0; i < g.px.size(); ++i) {
    const Vec3 d = g.dir(i);
    const double ground = d.z() < 0 ? -o.z() / d.z() : kInf;
    const double ra = ref_hit(a, t, o, d), rp = ref_hit(p, t, o, d);
    const int expect = ra < std::min(ground, rp) ? 3 : rp < std::min(ground, ra) ? 7 : 0;
    const auto& x = g.px[i];
    if (expect) ++hits[expect == 3 ? 0 : 1];
    if (!x.ret) continue;
    INFO("pixel " << i << " label " << x.label << " expected " << expect);
    REQUIRE(x.label == expect);
    if (expect == 0) continue;
    ++labelled[expect == 3 ? 0 : 1];
    worst = std::max(worst, std::abs(g.range(i) - (expect == 3 ? ra : rp)));
  }
  INFO("car: " << labelled[0] << " of " << hits[0] << " rays; walker: " << labelled[1] << " of " << hits[1]
               << "; worst range error " << worst << " m");
  CHECK(hits[0] > 100);
  CHECK(hits[1] > 10);
  // Grazing and weak returns may drop; nearly every ray on an actor returns with its label.
  CHECK(labelled[0] >= 0.95 * hits[0]);
  CHECK(labelled[1] >= 0.9 * hits[1]);
  CHECK(worst < 1e-3);  // float ray casting against the double reference
}

TEST_CASE("an actor hides the static returns behind it", "[sim][actors]") {
  sim::Scene scene;
  scene.add(sim::Primitive::make_box(sim::V3(25.f, 0.f, 4.f), sim::V3(0.5f, 30.f, 4.f), 0.f,
                                     sim::Material::concrete, 0.4f));  // a wall across the view
  scene.build();
  const GridScan before(scene);
  const sim::ActorTrack a = car(12.0, 0.5, 0.1);
  sim::place_actors(scene, {a}, a.t_ref);
  const GridScan after(scene);
  size_t occluded = 0, wall_before = 0, wall_after = 0;
  for (size_t i = 0; i < before.px.size(); ++i) {
    const bool on_wall = before.px[i].ret && before.range(i) > 20.0 && before.px[i].label == 0;
    const bool still_wall = after.px[i].ret && after.range(i) > 20.0 && after.px[i].label == 0;
    wall_before += on_wall;
    wall_after += still_wall;
    const double ra = ref_hit(a, a.t_ref, after.T.translation(), after.dir(i));
    if (ra == kInf) {
      // Away from the car nothing changes, bit for bit.
      REQUIRE(after.px[i].ret == before.px[i].ret);
      if (after.px[i].ret) REQUIRE(after.range(i) == before.range(i));
      continue;
    }
    if (!on_wall) continue;
    ++occluded;
    INFO("pixel " << i);
    REQUIRE_FALSE(still_wall);  // no static return behind the car
    if (after.px[i].ret) {
      CHECK(after.px[i].label == 3);
      CHECK(after.range(i) == Approx(ra).margin(1e-3));
    }
  }
  INFO(occluded << " wall returns hidden by the car");
  CHECK(occluded > 50);
  CHECK(wall_after == wall_before - occluded);
}

TEST_CASE("actor configuration: bad values and unknown keys are refused, naming the key", "[sim][actors]") {
  using sim::ActorsConfig;
  const ActorsConfig ok = ActorsConfig::from_json(Json{{"vehicles", 3}, {"crossing", 1}}, "seq");
  CHECK(ok.vehicles == 3);
  CHECK(ok.crossing == 1);
  CHECK(ok.pedestrians == 0);
  CHECK(ActorsConfig::from_json(ok.to_json(), "again").to_json() == ok.to_json());
  CHECK_FALSE(ActorsConfig{}.any());  // off by default
  const std::pair<Json, std::string> bad[] = {
      {Json{{"vehicles", 2}, {"vehicle_sped_max", 3.0}}, "vehicle_sped_max"},
      {Json{{"vehicles", -1}}, "vehicles"},
      {Json{{"pedestrians", 5000}}, "pedestrians"},
      {Json{{"crossing", "two"}}, "crossing"},
      {Json{{"vehicle_speed_min", 12.0}, {"vehicle_speed_max", 8.0}}, "vehicle_speed_min"},
      {Json{{"pedestrian_curvature_max", -0.1}}, "pedestrian_curvature_max"},
  };
  for (const auto& [j, key] : bad) {
    INFO(j.dump());
    try {
      ActorsConfig::from_json(j, "sequences.json: kitti360-dyn-x.actors");
      FAIL("accepted");
    } catch (const ConfigError& e) {
      CHECK_THAT(e.what(), Catch::Contains("'" + key + "'"));
      CHECK_THAT(e.what(), Catch::Contains("kitti360-dyn-x.actors"));
    }
  }
}
