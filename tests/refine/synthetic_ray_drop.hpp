// A small synthetic ray-drop problem for the refinement tests: frames of rendered (return
// probability, intensity, depth) and the observed return masks, where the mask is a known
// function of the inputs and their neighbourhood that thresholding the probability misses:
//   dropped where intensity < 0.3 (weak returns; the rendered probability knows this one, with
//   noise), where depth > 60 m (out of range), and next to depth edges > 4 m (mixed pixels).
#pragma once
#include <cstdint>
#include <vector>

namespace sgnlf::test {

struct RayDropFrames {
  int n = 0, h = 0, w = 0;
  std::vector<float> inputs;  // n × h × w × 3: probability, intensity, depth (m)
  std::vector<float> masks;   // n × h × w: 1 = return
};

RayDropFrames synthetic_ray_drop(int n, int h, int w, uint64_t seed);

// Mean BCE (double) and accuracy at 0.5 of probabilities against masks.
double mean_bce(const std::vector<float>& probs, const std::vector<float>& masks);
double accuracy(const std::vector<float>& probs, const std::vector<float>& masks);
// Channel 0 of the inputs (the rendered probability alone).
std::vector<float> input_probability(const RayDropFrames& f);

}  // namespace sgnlf::test
