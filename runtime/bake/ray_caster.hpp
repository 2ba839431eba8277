// The OpenCL ray caster of a baked scene (kernels/bake/raycast.cl, docs/baking.md): the scene
// uploaded once, then any number of ray sets cast against it. Host reference (tests only):
// tests/bake/raycast_reference.hpp.
#pragma once
#include <vector>

#include "bake/baked_scene.hpp"
#include "cl/runtime.hpp"

namespace sgnlf::bake {

class RayCaster {
 public:
  // Uploads the scene's index and vertices (validated).
  RayCaster(cl::Runtime& rt, const BakedScene& scene);

  // Floats per ray of out: depth in metres, return probability, intensity, opacity Σ w, the
  // depths where the accumulated weight first reaches 1/8, 3/8, 5/8, 7/8 (−1: not reached), the
  // median depth and the weight-normalised depth variance (m²), as the field's evaluation
  // renders them (kernels/bake/raycast.cl).
  static constexpr int kOutputs = 10;
  // Enqueues n rays (origins and unit directions n × 3 on the device, world metres) into out
  // (n × kOutputs). No wait.
  cl::Event cast(const cl::Buffer& origins, const cl::Buffer& dirs, int n, cl::Buffer& out);
  // The same from host arrays; blocking.
  std::vector<float> cast(const std::vector<float>& origins, const std::vector<float>& dirs);

  // Bytes of the scene on the device.
  size_t device_bytes() const { return bytes_; }

 private:
  cl::Runtime& rt_;
  cl::Kernel k_;
  cl::Buffer index_, verts_, mask_;
  cl_float4 lo_{};
  cl_int4 dims_{};
  float voxel_, near_, far_, step_, stop_;
  int brick_;
  size_t bytes_ = 0;
  cl::Buffer o_, d_, out_;  // the host-array path's buffers, grown on demand
  int cap_ = 0;
};

}  // namespace sgnlf::bake
