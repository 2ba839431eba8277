// The moving actors' ground truth on disk (see actor_truth.hpp).
#include "datasets/actor_truth.hpp"

#include <cstdio>
#include <filesystem>

#include "core/config.hpp"
#include "core/error.hpp"
#include "io/scan_io.hpp"

namespace sgnlf {
namespace fs = std::filesystem;

std::string actor_truth_path(const std::string& root) {
  return (fs::path(root) / "ground_truth" / "actors.json").string();
}

std::string actor_labels_path(const std::string& root, int frame) {
  char b[32];
  std::snprintf(b, sizeof(b), "%010d.bin", frame);
  return (fs::path(root) / "ground_truth" / "labels" / b).string();
}

void write_labels(const std::string& path, const std::vector<uint16_t>& labels) {
  std::vector<unsigned char> bytes(labels.size() * 2);
  for (size_t i = 0; i < labels.size(); ++i) {
    bytes[2 * i] = static_cast<unsigned char>(labels[i] & 0xFFu);
    bytes[2 * i + 1] = static_cast<unsigned char>(labels[i] >> 8);
  }
  io::write_file_bytes(path, bytes.data(), bytes.size());
}

std::vector<uint16_t> read_labels(const std::string& path) {
  const std::vector<char> bytes = io::read_file_bytes(path, io::kMaxScanBytes);
  if (bytes.size() % 2 != 0)
    throw IoError(path + ": " + std::to_string(bytes.size()) + " bytes, not a whole number of uint16 labels");
  std::vector<uint16_t> labels(bytes.size() / 2);
  for (size_t i = 0; i < labels.size(); ++i)
    labels[i] = uint16_t(static_cast<unsigned char>(bytes[2 * i]) |
                         (static_cast<unsigned char>(bytes[2 * i + 1]) << 8));
  return labels;
}

void write_actor_truth(const std::string& root, const std::vector<sim::ActorTrack>& actors,
                       double clock_offset_s, const std::vector<Frame>& frames) {
  Json tracks = Json::array(), per_frame = Json::array();
  for (const auto& a : actors) tracks.push_back(a.to_json());
  fs::create_directories(fs::path(root) / "ground_truth" / "labels");
  for (const auto& f : frames) {
    require(f.labels.size() == f.points.size(), "write_actor_truth: frame " + std::to_string(f.id) + " has " +
                                                    std::to_string(f.labels.size()) + " labels for " +
                                                    std::to_string(f.points.size()) + " points");
    Json boxes = Json::array();
    for (const auto& b : f.actors) {
      double v[12];
      pose_to_3x4(b.T_world_actor, v);
      boxes.push_back(Json{{"id", b.id}, {"T_world_actor", std::vector<double>(v, v + 12)}});
    }
    per_frame.push_back(Json{{"frame", f.id}, {"timestamp_s", f.timestamp_s}, {"actors", boxes}});
    write_labels(actor_labels_path(root, f.id), f.labels);
  }
  write_json_file(actor_truth_path(root),
                  Json{{"format", "sgnlf-actors"}, {"version", 1},
                       {"note", "T_world_actor: 3x4 row-major, box centre, x along the motion; actor "
                                "time = timestamp_s + clock_offset_s; labels/<frame>.bin: uint16 per "
                                "scan point, 0 static, k actor k"},
                       {"clock_offset_s", clock_offset_s}, {"actors", tracks}, {"frames", per_frame}});
}

std::map<int, std::vector<ActorBox>> read_actor_boxes(const std::string& path) {
  const Json j = load_json_file(path);
  std::map<int, std::vector<ActorBox>> out;
  std::string at = "";
  try {
    std::map<int, ActorBox> shape;  // id → kind and half extents
    at = "actors";
    for (const auto& a : j.at("actors")) {
      ActorBox b;
      b.id = a.at("id").get<int>();
      b.kind = a.at("kind").get<std::string>();
      const auto h = a.at("half_extents").get<std::vector<double>>();
      if (h.size() != 3) throw IoError("half_extents must hold 3 numbers");
      b.half_extents = Vec3(h[0], h[1], h[2]);
      shape[b.id] = b;
    }
    for (const auto& f : j.at("frames")) {
      const int id = f.at("frame").get<int>();
      at = "frames (frame " + std::to_string(id) + ")";
      auto& boxes = out[id];
      for (const auto& a : f.at("actors")) {
        const int aid = a.at("id").get<int>();
        if (!shape.count(aid)) throw IoError("actor " + std::to_string(aid) + " is not in 'actors'");
        const auto v = a.at("T_world_actor").get<std::vector<double>>();
        if (v.size() != 12) throw IoError("T_world_actor must hold 12 numbers");
        ActorBox b = shape.at(aid);
        b.T_world_actor = pose_from_3x4(v.data());
        boxes.push_back(b);
      }
    }
  } catch (const IoError& e) {
    throw IoError(path + ": " + at + ": " + e.what());
  } catch (const std::exception& e) {
    throw IoError(path + ": " + (at.empty() ? "" : at + ": ") + e.what());
  }
  return out;
}

}  // namespace sgnlf
