// Loading a dataset from disk with layout autodetection: the synthetic layout (KITTI-360-like,
// with sgnlf_dataset.json), KITTI-360 raw, KITTI odometry, nuScenes v1.0-mini, or a single scan
// file / folder of scans (no poses). Every frame gets its range image (protocol §1) and the
// protocol split (protocol §3).
#pragma once
#include <string>
#include <vector>

#include "core/config_choices.hpp"
#include "core/config_fwd.hpp"
#include "datasets/dataset.hpp"

namespace sgnlf {

struct LoadOptions {
  std::string sequence;   // KITTI-360 drive / KITTI odometry "NN" / nuScenes scene name; "" = default
  std::string frequency;  // "standard" | "low"; "" = the dataset's own (synthetic), else from
                          // rate_hz when set (<= 5 Hz low), else "standard"
  int start = -1;         // first frame id; −1 = default (KITTI-360: 1538, others: first frame)
  int frames = -1;        // −1 = protocol count (64 standard, 36 low), fewer if the data is shorter
  int stride = -1;        // −1 = 1 standard, native rate / 2 Hz for low (KITTI 5, nuScenes 10)
  std::string sensor;     // "" = the layout's sensor (a plain folder: estimated from the scans,
                          // sensor_estimate.hpp); else a preset name or a sensor JSON file
  // The scan rate wanted, Hz; 0 = the data's. Layouts with a clock (KITTI, KITTI-360, nuScenes,
  // synthetic) keep their sensor's rate (it times each sweep) and take every
  // round(native / rate_hz)-th frame unless `stride` is set; plain folders have no clock: their
  // sensor's rate_hz and the frames' timestamps take it.
  double rate_hz = 0.0;
  bool load_points = true;
  // Test views as positions in the loaded window (0 = its first frame), replacing the protocol
  // split (protocol §3), e.g. for a short real slice that holds none of frames 13, 26, 39, 52.
  // Empty = the protocol split. At least one frame must stay for training.
  std::vector<int> test_frames;

  // The keys (core/config_fields.hpp), each written only when set away from its default;
  // the rules on their values are validate()'s.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v("sequence", s.sequence, config::omit_when<std::string>(""));
    v("frequency", s.frequency, config::omit_when<std::string>(""));
    v("start", s.start, config::omit_when(-1));
    v("frames", s.frames, config::omit_when(-1));
    v("stride", s.stride, config::omit_when(-1));
    v("sensor", s.sensor, config::omit_when<std::string>(""));
    v("rate_hz", s.rate_hz, config::omit_when(0.0));
    v("test_frames", s.test_frames, config::omit_when(std::vector<int>{}));  // integers
  }

  void validate() const;
  bool is_default() const;
  // The keys set away from their defaults (sequence, frequency, start, frames, stride, sensor,
  // rate_hz, test_frames; load_points is not data selection and is not written).
  Json to_json() const;
  // Keys as written by to_json(), all optional, unknown keys rejected; validated.
  static LoadOptions from_json(const Json& j, const std::string& where);
};

bool operator==(const LoadOptions& a, const LoadOptions& b);

// "synthetic", "kitti360", "kitti-odometry", "nuscenes", "scans"; IoError when none matches.
std::string detect_layout(const std::string& path);

Dataset load_dataset(const std::string& path, const LoadOptions& opt = {});

}  // namespace sgnlf
