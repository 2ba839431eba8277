// Synthetic twins of the protocol's sequences: named sequences (--list), the in-memory
// simulate() and the on-disk writer. The layout on disk is KITTI-360's (see datasets/README.md)
// plus sensor.json and sgnlf_dataset.json, so load_dataset reads it through the real loader.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config.hpp"
#include "datasets/dataset.hpp"
#include "datasets/sim_lidar.hpp"

namespace sgnlf {

struct NamedSequence {
  std::string name, preset, frequency, layout;  // layout: "street" or "loop"
  int frames = 64;
  int moving_vehicles = 0;
  std::string description;
};

const std::vector<NamedSequence>& named_sequences();
const NamedSequence& find_sequence(const std::string& name);  // ConfigError listing known names
Json named_sequences_json();  // what datasets/sequences.json holds

struct SimOptions {
  std::string sequence = "kitti360-low-a";
  std::string preset;     // "" = the sequence's preset
  std::string frequency;  // "" = the sequence's
  uint64_t seed = 1;
  int frames = -1;        // −1 = the sequence's (64 standard, 36 low)
  int width = -1;         // −1 = the sensor's; smaller for quick CI runs
  int height = -1;
  int moving_vehicles = -1;  // −1 = the sequence's
  std::string sensor_json;   // user-defined sensor (overrides the preset)
  int threads = 0;
  sim::LidarModel lidar;

  void validate() const;
};

// Everything the simulator resolved (what is written to sgnlf_dataset.json).
struct SimResult {
  Dataset dataset;
  Json metadata;
  sim::DropStats drops;
};

SimResult simulate(const SimOptions& opt);
// simulate(opt).dataset
Dataset simulate_dataset(const SimOptions& opt);
// Writes the KITTI-360-like layout (scans, poses, calibration, sensor, metadata, GT).
void write_synthetic(const SimResult& r, const std::string& dir);

}  // namespace sgnlf
