// The named synthetic sequences (see sim_sequences.hpp).
#include "datasets/sim_sequences.hpp"

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf {

namespace {
// What the real-like sequences add; the drop causes' rates are in simulate.cpp.
const SimRealism kRealLike{true, 10, true, true, 6.0};

// The moving actors of a dynamic twin: cars, people on the sidewalks, people crossing.
sim::ActorsConfig actors(int vehicles, int pedestrians, int crossing) {
  sim::ActorsConfig a;
  a.vehicles = vehicles;
  a.pedestrians = pedestrians;
  a.crossing = crossing;
  return a;
}

// Twins of LiDAR4D's dynamic KITTI-360 windows (2013_05_28_drive_0000, frames start..start+50).
NamedSequence dynamic_twin(int start, sim::ActorsConfig a) {
  const std::string s = std::to_string(start);
  return {"kitti360-dyn-" + s, "kitti360", "standard", "straight", 51, 0,
          "dynamic, twin of LiDAR4D's KITTI-360 window " + s + "-" + std::to_string(start + 50) +
              ": 51 frames at 10 Hz, test frames 10, 20, 30, 40; labelled moving cars and pedestrians",
          {}, a, "dynamic"};
}
}  // namespace

Json SimRealism::to_json() const {
  return Json{{"motion_distortion", motion_distortion}, {"pedestrians", pedestrians}, {"vegetation", vegetation},
              {"real_drop", real_drop}, {"extra_setback_m", extra_setback_m}};
}

const std::vector<NamedSequence>& named_sequences() {
  static const std::vector<NamedSequence> seqs = {
      {"kitti360-1538", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 1538"},
      {"kitti360-1728", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 1728"},
      {"kitti360-1908", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 1908"},
      {"kitti360-3353", "kitti360", "standard", "street", 64, 0, "standard frequency, twin of KITTI-360 start 3353"},
      {"kitti360-low-a", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-low-b", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-low-c", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-low-d", "kitti360", "low", "street", 36, 0, "low frequency (2 Hz), street with turns"},
      {"kitti360-loop", "kitti360", "low", "loop", 36, 0, "low frequency, drives around a block and revisits its start"},
      {"kitti360-dynamic", "kitti360", "standard", "street", 64, 6, "standard frequency with moving vehicles"},
      {"nuscenes-low-a", "nuscenes", "low", "street", 36, 0, "nuScenes-like, 2 Hz keyframes"},
      {"nuscenes-low-b", "nuscenes", "low", "street", 36, 0, "nuScenes-like, 2 Hz keyframes"},
      {"nuscenes-low-c", "nuscenes", "low", "street", 36, 0, "nuScenes-like, 2 Hz keyframes"},
      {"nuscenes-loop", "nuscenes", "low", "loop", 36, 0, "nuScenes-like loop around a block"},
      {"nuscenes-dynamic", "nuscenes", "low", "street", 36, 6, "nuScenes-like with moving vehicles"},
      {"nuscenes-real-like-a", "nuscenes", "low", "street", 36, 8,
       "nuScenes-like, 2 Hz, with what real scans have: motion distortion, traffic, pedestrians, bushes, real-like ray drop",
       kRealLike},
      {"kitti360-real-like-a", "kitti360", "low", "street", 36, 8,
       "KITTI-like, 2 Hz, with motion distortion, traffic, pedestrians, bushes, real-like ray drop", kRealLike},
      dynamic_twin(2350, actors(4, 4, 1)),
      dynamic_twin(4950, actors(6, 3, 1)),
      dynamic_twin(8120, actors(3, 6, 2)),
      dynamic_twin(10200, actors(5, 4, 1)),
      dynamic_twin(10750, actors(4, 2, 2)),
      dynamic_twin(11400, actors(6, 5, 1)),
  };
  return seqs;
}

const NamedSequence& find_sequence(const std::string& name) {
  std::string known;
  for (const auto& s : named_sequences()) {
    if (s.name == name) return s;
    known += (known.empty() ? "" : ", ") + s.name;
  }
  throw ConfigError("unknown synthetic sequence '" + name + "' (known: " + known + ")");
}

Json named_sequences_json() {
  Json a = Json::array();
  for (const auto& s : named_sequences()) {
    Json j{{"name", s.name}, {"preset", s.preset}, {"frequency", s.frequency}, {"layout", s.layout},
           {"frames", s.frames}, {"moving_vehicles", s.moving_vehicles}, {"description", s.description}};
    if (s.realism.any()) j["realism"] = s.realism.to_json();
    if (s.actors.any()) j["actors"] = s.actors.to_json();
    if (s.split != "protocol") j["split"] = s.split;
    a.push_back(j);
  }
  return a;
}

}  // namespace sgnlf
