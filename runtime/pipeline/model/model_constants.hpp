// Constants shared by the LidarNerfModel sources (model.cpp, model_sampling.cpp); private to
// the pipeline module.
#pragma once

namespace sgnlf::pipeline::model_detail {

constexpr int kDensStride = 16;  // density MLP output: σ logit + 15 geometric features
constexpr float kSceneBound = 1.0f;  // normalised scene box (protocol §2)
// σ logit of samples behind early ray termination: σ = exp(−100) ≈ 4e-44, α = 0 in float.
constexpr float kDeadLogit = -100.0f;
// Head logits of samples outside the head band: sigmoid(−30) ≈ 9e-14, LiDAR-NeRF's zero.
constexpr float kOffLogit = -30.0f;

}  // namespace sgnlf::pipeline::model_detail
