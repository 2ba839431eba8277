// The named synthetic sequences (`sgnlf simulate --list`, datasets/sequences.json) and the
// opt-in realism a sequence may ask for (what real scans have and the first twins
// lacked). Sequences without realism are simulated exactly as before it existed; likewise
// without moving actors (sim_actors.hpp) and with the protocol's split.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "core/config_fwd.hpp"
#include "datasets/sim_actors.hpp"

namespace sgnlf {

struct SimRealism {
  // Points timed by azimuth over the sweep (Sensor::sweep, 1 / rate_hz long) and cast from the
  // pose interpolated at that time, stored uncompensated (datasets/sim_sweep.hpp).
  bool motion_distortion = false;
  int pedestrians = 0;      // people walking along the sidewalks (moving cylinders)
  bool vegetation = false;  // hedges and bushes: irregular foliage blobs along the sidewalks
  bool real_drop = false;   // the real-scan ray-drop causes (sim::LidarModel, simulate.cpp)
  double extra_setback_m = 0.0;  // buildings this much farther from the road: more open streets
  bool any() const { return motion_distortion || pedestrians > 0 || vegetation || real_drop || extra_setback_m > 0; }
  Json to_json() const;
};

// The test frames of a sequence: "protocol" (protocol §3, by frequency) or "dynamic" (LiDAR4D's
// dynamic KITTI-360 set: every 10th frame strictly inside the window, 10, 20, 30 and 40 of 51;
// protocol.hpp dynamic_split).
struct NamedSequence {
  NamedSequence(std::string name_, std::string preset_, std::string frequency_, std::string layout_, int frames_,
                int moving_vehicles_, std::string description_, SimRealism realism_ = {},
                sim::ActorsConfig actors_ = {}, std::string split_ = "protocol")
      : name(std::move(name_)), preset(std::move(preset_)), frequency(std::move(frequency_)),
        layout(std::move(layout_)), frames(frames_), moving_vehicles(moving_vehicles_),
        description(std::move(description_)), realism(realism_), actors(actors_), split(std::move(split_)) {}
  std::string name, preset, frequency, layout;  // layout: "street", "loop" or "straight"
  int frames = 64;
  int moving_vehicles = 0;  // the older unlabelled movers (sim_street.hpp)
  std::string description;
  SimRealism realism;
  sim::ActorsConfig actors;  // labelled moving actors with ground truth (none by default)
  std::string split = "protocol";
};

const std::vector<NamedSequence>& named_sequences();
const NamedSequence& find_sequence(const std::string& name);  // ConfigError listing known names
Json named_sequences_json();  // what datasets/sequences.json holds

}  // namespace sgnlf
