// Constants and a buffer helper shared by the LidarNerfModel sources and its launchers
// (model.cpp, encoding_reuse.cpp, sample_compaction.cpp, coarse_waves.cpp, head_band.cpp);
// private to the pipeline module.
#pragma once
#include <algorithm>
#include <cstddef>

#include "cl/runtime.hpp"

namespace sgnlf::pipeline::model_detail {

constexpr int kDensStride = 16;  // density MLP output: σ logit + 15 geometric features
constexpr float kSceneBound = 1.0f;  // normalised scene box (protocol §2)
// σ logit of samples behind early ray termination: σ = exp(−100) ≈ 4e-44, α = 0 in float.
constexpr float kDeadLogit = -100.0f;
// Head logits of samples outside the head band: sigmoid(−30) ≈ 9e-14, LiDAR-NeRF's zero.
constexpr float kOffLogit = -30.0f;

// A device buffer of n floats (or int32s), at least one.
inline cl::Buffer floats(cl::Runtime& rt, size_t n) {
  return cl::Buffer(rt, std::max<size_t>(n, 1) * 4);
}

}  // namespace sgnlf::pipeline::model_detail
