// Procedural urban street grown from a seed: a road centreline (straights and arcs, or a closed
// block loop), lanes with markings, curbs and sidewalks, building facades of varied setback,
// height and material, parked cars, poles, trees, walls and small clutter; moving vehicles and
// the ego trajectory (turns, speed changes) along the road.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "datasets/sim_scene.hpp"
#include "geometry/se3.hpp"

namespace sgnlf::sim {

// Road centreline sampled every `ds` metres; closed paths wrap around.
struct Path {
  std::vector<Eigen::Vector2d> pts;
  std::vector<double> heading;
  double ds = 0.5;
  bool closed = false;
  double length() const { return ds * double(pts.size() - 1); }
  Eigen::Vector2d point(double s) const;
  double heading_at(double s) const;
  Eigen::Vector2d left(double s) const;  // unit normal to the left of the driving direction
  // Distance from q to the centreline (brute force over every 4th sample).
  double distance(const Eigen::Vector2d& q) const { return (nearest(q) - q).norm(); }
  Eigen::Vector2d nearest(const Eigen::Vector2d& q) const;
};

struct MovingVehicle {
  double s0 = 0, speed = 0, lateral = 0;  // arc position at t = 0, m/s along the path, offset
  double length = 4.4, width = 1.8, reflectance = 0.4;
};

struct Pedestrian {
  double s0 = 0, speed = 0, lateral = 0;  // arc position at t = 0, m/s along the path, offset
  double radius = 0.25, height = 1.75, reflectance = 0.3;
};

struct StreetWorld {
  Scene scene;
  Path path;
  double road_half_width = 5.0, sidewalk_width = 3.0;
  double ego_start_s = 0, ego_lateral = -2.0;
  double extra_setback_m = 0.0;  // added to every building's setback (StreetConfig)
  std::vector<MovingVehicle> movers;
  std::vector<Pedestrian> walkers;
  // Replaces scene.dynamic with the moving vehicles and pedestrians at time t.
  void place_movers(double t_s);
};

struct StreetConfig {
  // "street" (open road with turns), "loop" (block loop) or "straight" (one straight road)
  std::string layout = "street";
  double drive_length_m = 80;     // expected ego travel; the road extends 90 m beyond it
  int moving_vehicles = 0;
  int pedestrians = 0;      // opt-in (sim_street_life.cpp)
  bool vegetation = false;  // opt-in hedges and bushes (sim_street_life.cpp)
  double extra_setback_m = 0.0;  // opt-in: buildings farther from the road (open, real-like streets)
  uint64_t seed = 1;
};

StreetWorld generate_street(const StreetConfig& cfg);

// Opt-in street life, each from its own Rng stream so the rest of the world is
// unchanged: hedges and bushes (clusters of foliage ellipsoids) at the back of the sidewalks,
// added before the scene is built; people walking along the sidewalks.
void add_vegetation(StreetWorld& w, uint64_t seed);
void add_pedestrians(StreetWorld& w, int count, uint64_t seed);

// Ego motion: speed keypoints every ~3 s in [v_min, v_max] with smooth (cosine) blends,
// integrated along the road; returns T_world_lidar at each time (sensor at `height` m).
struct DriveConfig {
  double v_min = 4.0, v_max = 10.0, sensor_height_m = 1.73;
  uint64_t seed = 1;
};
std::vector<Pose> drive(const StreetWorld& w, const DriveConfig& cfg, const std::vector<double>& times_s);

}  // namespace sgnlf::sim
