// Moving actors (see sim_actors.hpp). Every draw is a named value from Rng(seed, 6), in a fixed
// order (core/rng.hpp: never two draws in one argument list).
#include "core/config_fields.hpp"
#include "datasets/sim_actors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::sim {

void ActorsConfig::validate() const {
  const std::string w = "actors";
  config::check_fields(*this, w);
  if (vehicle_speed_min > vehicle_speed_max)
    throw ConfigError(w + ": 'vehicle_speed_min' = " + std::to_string(vehicle_speed_min) +
                      " above 'vehicle_speed_max' = " + std::to_string(vehicle_speed_max));
  if (pedestrian_speed_min > pedestrian_speed_max)
    throw ConfigError(w + ": 'pedestrian_speed_min' = " + std::to_string(pedestrian_speed_min) +
                      " above 'pedestrian_speed_max' = " + std::to_string(pedestrian_speed_max));
}

ActorsConfig ActorsConfig::from_json(const Json& j, const std::string& where) {
  if (!j.is_object()) throw ConfigError(where + ": expected an object of actor settings");
  ActorsConfig c;
  ConfigReader r(j, where);
  config::read_fields_here(r, c);
  r.finish();
  try {
    c.validate();
  } catch (const ConfigError& e) {
    throw ConfigError(where + ": " + e.what());
  }
  return c;
}

const char* actor_kind_name(ActorKind k) { return k == ActorKind::vehicle ? "vehicle" : "pedestrian"; }

Eigen::Vector2d ActorTrack::position(double t_s) const {
  const double d = speed * (t_s - t_ref), turn = curvature * d;
  const double chord = std::abs(turn) < 1e-12 ? d : 2.0 * std::sin(0.5 * turn) / curvature;
  const double a = yaw_ref + 0.5 * turn;
  return xy_ref + chord * Eigen::Vector2d(std::cos(a), std::sin(a));
}

double ActorTrack::yaw(double t_s) const { return yaw_ref + curvature * speed * (t_s - t_ref); }

Pose ActorTrack::pose(double t_s, double ground_z) const {
  const Eigen::Vector2d p = position(t_s);
  Pose T = Pose::Identity();
  T.linear() = Eigen::AngleAxisd(yaw(t_s), Vec3::UnitZ()).toRotationMatrix();
  T.translation() = Vec3(p.x(), p.y(), ground_z + half.z());
  return T;
}

Primitive ActorTrack::primitive(double t_s, double ground_z) const {
  const Eigen::Vector2d p = position(t_s);
  Primitive q = kind == ActorKind::vehicle
                    ? Primitive::make_box(V3(float(p.x()), float(p.y()), float(ground_z + half.z())),
                                          half.cast<float>(), float(yaw(t_s)), Material::car_paint,
                                          float(reflectance))
                    : Primitive::make_cylinder(float(p.x()), float(p.y()), float(ground_z),
                                               float(ground_z + 2.0 * half.z()), float(half.x()),
                                               Material::plastic, float(reflectance));
  q.label = id;
  return q;
}

ActorBox ActorTrack::box(double t_s, double ground_z) const {
  ActorBox b;
  b.id = id;
  b.kind = actor_kind_name(kind);
  b.T_world_actor = pose(t_s, ground_z);
  b.half_extents = half;
  return b;
}

Json ActorTrack::to_json() const {
  return Json{{"id", id}, {"kind", actor_kind_name(kind)},
              {"half_extents", {half.x(), half.y(), half.z()}}, {"reflectance", reflectance},
              {"trajectory", {{"t_ref_s", t_ref}, {"x_ref", xy_ref.x()}, {"y_ref", xy_ref.y()},
                              {"yaw_ref", yaw_ref}, {"speed_mps", speed}, {"curvature_per_m", curvature}}}};
}

namespace {

// Arc position of the centreline point nearest to q (sample nearest, then along its segment).
double arc_position(const Path& p, const Eigen::Vector2d& q) {
  size_t best = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < p.pts.size(); ++i) {
    const double d = (p.pts[i] - q).squaredNorm();
    if (d < bd) { bd = d; best = i; }
  }
  const size_t i = std::min(best, p.pts.size() - 2);
  const Eigen::Vector2d ab = p.pts[i + 1] - p.pts[i];
  const double f = std::clamp((q - p.pts[i]).dot(ab) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return p.ds * (double(i) + f);
}

// A frame's index drawn in [lo, hi] of the sequence (fractions of it).
size_t draw_frame(Rng& rng, size_t n, float lo, float hi) {
  const float u = rng.uniform(lo, hi);
  return std::min(n - 1, size_t(u * float(n - 1) + 0.5f));
}

}  // namespace

std::vector<ActorTrack> generate_actors(const ActorsConfig& cfg, const StreetWorld& w,
                                        const std::vector<double>& times_s,
                                        const std::vector<Pose>& T_world_ego, double ego_v_max,
                                        uint64_t seed) {
  cfg.validate();
  std::vector<ActorTrack> out;
  if (!cfg.any()) return out;
  require(!times_s.empty() && times_s.size() == T_world_ego.size(),
          "generate_actors: " + std::to_string(times_s.size()) + " times for " +
              std::to_string(T_world_ego.size()) + " ego poses");
  Rng rng(seed, 6);
  const size_t n = times_s.size();
  auto ego_s = [&](size_t k) {
    const Vec3 t = T_world_ego[k].translation();
    return arc_position(w.path, Eigen::Vector2d(t.x(), t.y()));
  };
  const double wr = w.road_half_width, sw = w.sidewalk_width;
  const double lane_out = (wr - 2.2) / 2;  // the oncoming lane's centre (the ego's, mirrored)
  auto at = [&](double s, double lat) { return Eigen::Vector2d(w.path.point(s) + w.path.left(s) * lat); };
  uint16_t id = 1;
  for (int i = 0; i < cfg.vehicles; ++i) {
    ActorTrack a;
    a.id = id++;
    a.kind = ActorKind::vehicle;
    const float len = rng.uniform(3.9f, 4.9f), wid = rng.uniform(1.7f, 1.9f), hgt = rng.uniform(1.4f, 1.7f);
    a.half = Vec3(len / 2, wid / 2, hgt / 2);
    a.reflectance = rng.uniform(0.15f, 0.7f);
    const float kappa = rng.uniform(-1.f, 1.f);
    a.curvature = kappa * cfg.vehicle_curvature_max;
    if (i % 2 == 0) {  // oncoming: in the other lane at the drawn frame, level with the ego
      const size_t k = draw_frame(rng, n, 0.15f, 0.85f);
      const float along = rng.uniform(-2.f, 2.f);
      a.speed = rng.uniform(float(cfg.vehicle_speed_min), float(cfg.vehicle_speed_max));
      const double s = ego_s(k) + along;
      a.t_ref = times_s[k];
      a.xy_ref = at(s, lane_out);
      a.yaw_ref = w.path.heading_at(s) + M_PI;
    } else {  // ahead in the ego's lane at the first frame, faster than the ego can drive
      const float ahead = rng.uniform(10.f, 25.f);
      a.speed = ego_v_max + rng.uniform(1.f, 4.f);
      const double s = ego_s(0) + ahead + 12.0 * (i / 2);
      a.t_ref = times_s[0];
      a.xy_ref = at(s, w.ego_lateral);
      a.yaw_ref = w.path.heading_at(s);
    }
    out.push_back(a);
  }
  for (int i = 0; i < cfg.pedestrians; ++i) {  // along the sidewalks, both ways
    ActorTrack a;
    a.id = id++;
    a.kind = ActorKind::pedestrian;
    const float r = rng.uniform(0.2f, 0.3f), h = rng.uniform(1.5f, 1.9f);
    a.half = Vec3(r, r, h / 2);
    a.reflectance = rng.uniform(0.08f, 0.5f);
    const size_t k = draw_frame(rng, n, 0.f, 1.f);
    const float along = rng.uniform(-10.f, 40.f), into = rng.uniform(0.6f, float(std::max(0.7, sw - 0.5)));
    const float dir = rng.uniform(), kappa = rng.uniform(-1.f, 1.f);
    a.speed = rng.uniform(float(cfg.pedestrian_speed_min), float(cfg.pedestrian_speed_max));
    a.curvature = kappa * cfg.pedestrian_curvature_max;
    const double side = i % 2 == 0 ? 1.0 : -1.0, s = ego_s(k) + along;
    a.t_ref = times_s[k];
    a.xy_ref = at(s, side * (wr + into));
    a.yaw_ref = w.path.heading_at(s) + (dir < 0.5f ? 0.0 : M_PI);
    out.push_back(a);
  }
  for (int i = 0; i < cfg.crossing; ++i) {  // on the centreline ahead of the ego at the drawn frame
    ActorTrack a;
    a.id = id++;
    a.kind = ActorKind::pedestrian;
    const float r = rng.uniform(0.2f, 0.3f), h = rng.uniform(1.5f, 1.9f);
    a.half = Vec3(r, r, h / 2);
    a.reflectance = rng.uniform(0.08f, 0.5f);
    const size_t k = draw_frame(rng, n, 0.25f, 0.75f);
    const float ahead = rng.uniform(12.f, 25.f), kappa = rng.uniform(-1.f, 1.f);
    a.speed = rng.uniform(float(cfg.pedestrian_speed_min), float(cfg.pedestrian_speed_max));
    a.curvature = kappa * cfg.pedestrian_curvature_max;
    const double s = ego_s(k) + ahead;
    a.t_ref = times_s[k];
    a.xy_ref = at(s, 0.0);
    // From the ego's side of the road to the other: out of its lane before it arrives.
    a.yaw_ref = w.path.heading_at(s) + 0.5 * M_PI;
    out.push_back(a);
  }
  return out;
}

void place_actors(Scene& scene, const std::vector<ActorTrack>& actors, double t_s) {
  for (const auto& a : actors) scene.dynamic.push_back(a.primitive(t_s, scene.ground_z));
}

Json ActorsConfig::to_json() const { return config::write_fields(*this); }

}  // namespace sgnlf::sim
