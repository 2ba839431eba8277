// The time coordinate of LiDAR4D's 4D encodings (method.md §2): frame k of a sequence whose
// frames are first … first + frames − 1 sits at t = (k − first) / (frames − 1) ∈ [0, 1]; a
// one-frame sequence sits at t = 0. Frames outside the sequence are refused (sgnlf::Error).
#pragma once
#include <string>

#include "core/error.hpp"

namespace sgnlf::field {

inline float frame_time(int frame, int first, int frames) {
  if (frames < 1 || frame < first || frame - first >= frames)
    throw Error("frame_time: frame " + std::to_string(frame) + " outside the sequence [" +
                std::to_string(first) + ", " + std::to_string(first) + " + " +
                std::to_string(frames) + ")");
  return frames == 1 ? 0.0f : float(double(frame - first) / double(frames - 1));
}

}  // namespace sgnlf::field
