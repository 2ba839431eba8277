// The moving actors' ground truth in the synthetic layout (datasets/README.md "Moving actors"),
// written only for sequences with actors:
//   ground_truth/actors.json       the trajectories and, per frame, every actor's pose
//   ground_truth/labels/%010d.bin  one little-endian uint16 per point of the frame's scan file,
//                                  in its order: 0 the static world, k a return from actor k
// The loader fills Frame::actors and Frame::labels from them (labels filtered with the points).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "datasets/dataset.hpp"
#include "datasets/sim_actors.hpp"

namespace sgnlf {

std::string actor_truth_path(const std::string& root);             // <root>/ground_truth/actors.json
std::string actor_labels_path(const std::string& root, int frame);  // <root>/ground_truth/labels/<id>.bin

// Writes actors.json (tracks, the actors' clock offset, each frame's boxes) and the labels.
void write_actor_truth(const std::string& root, const std::vector<sim::ActorTrack>& actors,
                       double clock_offset_s, const std::vector<Frame>& frames);

// Per frame id, the actors' boxes of actors.json; IoError naming the file and entry when bad.
std::map<int, std::vector<ActorBox>> read_actor_boxes(const std::string& path);

void write_labels(const std::string& path, const std::vector<uint16_t>& labels);
// IoError naming the file when its size is not a whole number of labels.
std::vector<uint16_t> read_labels(const std::string& path);

}  // namespace sgnlf
