// `--sensor NAME|FILE` and `--frequency standard|low|HZ`, shared by every command that loads
// data (train, odometry, inspect, eval, posegraph, reconstruct); parsed by datasets/load_args.hpp when the command runs,
// so a bad value fails with a message naming the option and the value.
#pragma once
#include <string>

#include "apps/command.hpp"
#include "datasets/load_args.hpp"

namespace sgnlf::app {

struct SensorRateOptions {
  std::string sensor, frequency;

  void add(CLI::App& sub) {
    sub.add_option("--sensor", sensor,
                   "The sensor: a preset (kitti360 = HDL-64E, nuscenes = HDL-32E) or a sensor JSON "
                   "file (keys of sensor.json). Default: the layout's; for a plain folder of scans "
                   "(.bin, .pcd, .ply) an estimate from the scans (beams, field of view, azimuth "
                   "resolution, ranges; the preset it matches when one does), refused when the "
                   "scans do not cover 360° or the estimate keeps < 95 % of the points");
    sub.add_option("--frequency", frequency,
                   "standard | low | the scan rate in Hz (e.g. 2 for nuScenes keyframes). A rate "
                   "<= 5 Hz follows the protocol's low-frequency rules (36 frames, test frames "
                   "4, 12, 20), above them the standard ones (64 frames, every 13th). Layouts with "
                   "a clock (KITTI, KITTI-360, nuScenes, synthetic) take every round(native / HZ)-th "
                   "frame; a plain folder's frames are 1/HZ s apart (default: the times of a times.txt "
                   "or of the file names, e.g. nuScenes' microseconds, else the sensor's rate)");
  }
  // Sets opt.sensor / opt.rate_hz / opt.frequency for the options given; absent ones leave it.
  void apply(LoadOptions& opt) const {
    if (!sensor.empty()) set_sensor_arg(opt, sensor);
    if (!frequency.empty()) set_frequency_arg(opt, frequency);
  }
  bool any() const { return !sensor.empty() || !frequency.empty(); }
};

}  // namespace sgnlf::app
