// Moving actors of the dynamic twins: vehicles (one car-sized box each) and
// pedestrians (upright cylinders), each on its own trajectory, constant speed along a circular
// arc of constant, gentle curvature, known in closed form at any time. The simulator places
// them at each ray's time (per frame, or per slice of a sweep with motion distortion), every
// return from an actor carries the actor's id as its label, and every frame records the
// actors' true boxes. Off by default (ActorsConfig{} has none): a sequence without actors is
// simulated exactly as before they existed. The older unlabelled movers (StreetWorld::movers,
// walkers) are separate and unchanged.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "datasets/dataset.hpp"
#include "datasets/sim_street.hpp"

namespace sgnlf::sim {

struct ActorsConfig {
  int vehicles = 0;     // cars: even ones oncoming (they pass the ego), odd ones ahead in its lane
  int pedestrians = 0;  // people walking along the sidewalks
  int crossing = 0;     // people crossing the road ahead of the ego, through its view
  double vehicle_speed_min = 6.0, vehicle_speed_max = 11.0;      // m/s, oncoming cars
  double pedestrian_speed_min = 0.8, pedestrian_speed_max = 1.6;  // m/s
  // |curvature| bounds (1/m): a car drifts 0.8 m from its lane over ±45 m at 0.0008.
  double vehicle_curvature_max = 0.0008, pedestrian_curvature_max = 0.02;

  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("vehicles", s.vehicles, 0, 200);
    v("pedestrians", s.pedestrians, 0, 1000);
    v("crossing", s.crossing, 0, 200);
    v("vehicle_speed_min", s.vehicle_speed_min, 0.0, 40.0);
    v("vehicle_speed_max", s.vehicle_speed_max, 0.0, 40.0);
    v("pedestrian_speed_min", s.pedestrian_speed_min, 0.0, 5.0);
    v("pedestrian_speed_max", s.pedestrian_speed_max, 0.0, 5.0);
    v("vehicle_curvature_max", s.vehicle_curvature_max, 0.0, 0.05);
    v("pedestrian_curvature_max", s.pedestrian_curvature_max, 0.0, 0.5);
  }
  bool any() const { return vehicles + pedestrians + crossing > 0; }
  int count() const { return vehicles + pedestrians + crossing; }
  // Ranges and min <= max; ConfigError naming the key.
  void validate() const;
  Json to_json() const;
  // Unknown keys and wrong types refused (naming `where` and the key); validated.
  static ActorsConfig from_json(const Json& j, const std::string& where);
};

enum class ActorKind : uint8_t { vehicle, pedestrian };
const char* actor_kind_name(ActorKind k);

// At t_ref the actor is at xy_ref heading yaw_ref; it moves at `speed` (m/s) along the arc of
// curvature κ (1/m, > 0 turns left). With d = speed · (t − t_ref):
//   yaw(t) = yaw_ref + κ d,  xy(t) = xy_ref + c · (cos(yaw_ref + κd/2), sin(yaw_ref + κd/2)),
// c = 2 sin(κd/2) / κ the chord (= d when κ = 0).
struct ActorTrack {
  uint16_t id = 1;
  ActorKind kind = ActorKind::vehicle;
  Eigen::Vector2d xy_ref = Eigen::Vector2d::Zero();
  double yaw_ref = 0, t_ref = 0, speed = 0, curvature = 0;
  Eigen::Vector3d half = Eigen::Vector3d(2.2, 0.9, 0.75);  // box; pedestrian (r, r, height / 2)
  double reflectance = 0.4;

  Eigen::Vector2d position(double t_s) const;
  double yaw(double t_s) const;
  // T_world_actor: the box centre on the ground at ground_z, x along the motion.
  Pose pose(double t_s, double ground_z) const;
  Primitive primitive(double t_s, double ground_z) const;  // labelled with `id`
  ActorBox box(double t_s, double ground_z) const;
  Json to_json() const;
};

// The actors of `cfg` around the ego's drive: `times_s` the frames' times on the world clock,
// `T_world_ego` the ego's poses then (oncoming cars meet the ego and people cross ahead of it
// at drawn frames), `ego_v_max` its top speed (the cars ahead drive faster, never into it).
// Draws from Rng(seed, 6), a stream no other part of the world uses. Ids 1, 2, ...: vehicles,
// then walkers, then the people crossing.
std::vector<ActorTrack> generate_actors(const ActorsConfig& cfg, const StreetWorld& w,
                                        const std::vector<double>& times_s,
                                        const std::vector<Pose>& T_world_ego, double ego_v_max,
                                        uint64_t seed);

// Appends every actor's primitive at time t to scene.dynamic (after what is there).
void place_actors(Scene& scene, const std::vector<ActorTrack>& actors, double t_s);

}  // namespace sgnlf::sim
