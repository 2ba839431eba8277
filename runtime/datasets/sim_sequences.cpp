// The named synthetic sequences (see sim_sequences.hpp).
#include "datasets/sim_sequences.hpp"

#include "core/error.hpp"

namespace sgnlf {

namespace {
// What the real-like sequences add (issue 30); the drop causes' rates are in simulate.cpp.
const SimRealism kRealLike{true, 10, true, true, 6.0};
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
    a.push_back(j);
  }
  return a;
}

}  // namespace sgnlf
