// The state one forward of LidarNerfModel leaves for its backward (model.hpp): the samples it
// ran on (SampleSet: strategy, layout, live rows), the rows the LiDAR head ran on, and the
// model's pass number. The activations (sample buffers, MLP contexts) belong to the model;
// the context is valid for a backward only while no later pass has overwritten them, which the
// model checks by the pass number.
#pragma once
#include <cstdint>

#include "pipeline/model/sample_set.hpp"

namespace sgnlf::pipeline {

// Which rows the LiDAR head ran on: every sample, the live rows of early termination, or the
// band of samples with weight above render.head_weight_threshold (pipeline::HeadBand).
enum class HeadRows { All, Live, Band };

struct ForwardContext {
  SampleSet samples;
  HeadRows head = HeadRows::All;
  long head_rows = 0;  // rows the head ran on
  uint64_t pass = 0;   // the model's pass number of this forward; 0: none
  bool valid() const { return pass != 0; }
};

}  // namespace sgnlf::pipeline
