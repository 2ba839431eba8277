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
#include "datasets/sim_sequences.hpp"
#include "datasets/sim_sweep.hpp"

namespace sgnlf {

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
  // Realism on top of the sequence's (simulate --motion-distortion, --real-drop,
  // --pedestrians, --vegetation): each switches a part on, never off.
  SimRealism realism;
  // Moving actors: when any(), replace the sequence's own (sim_actors.hpp).
  sim::ActorsConfig actors;

  void validate() const;
};

// Everything the simulator resolved (what is written to sgnlf_dataset.json).
struct SimResult {
  Dataset dataset;
  Json metadata;
  sim::DropStats drops;
  // With motion distortion: each frame's sensor poses at its sweep's start and end (the truth
  // a deskewing can be checked against; metadata per_frame "sweep_twist_per_s" holds the
  // velocity). Empty otherwise.
  std::vector<sim::SweepPoses> sweeps;
  // The moving actors' trajectories (empty without actors); each frame's boxes and per-point
  // labels are in the dataset's frames. The actors' clock runs `actor_clock_offset_s` ahead of
  // the frames' timestamps (one sweep with motion distortion, else 0).
  std::vector<sim::ActorTrack> actors;
  double actor_clock_offset_s = 0.0;
};

SimResult simulate(const SimOptions& opt);
// simulate(opt).dataset
Dataset simulate_dataset(const SimOptions& opt);
// Writes the KITTI-360-like layout (scans, poses, calibration, sensor, metadata, GT; with
// actors also ground_truth/actors.json and ground_truth/labels/, datasets/README.md).
void write_synthetic(const SimResult& r, const std::string& dir);

}  // namespace sgnlf
