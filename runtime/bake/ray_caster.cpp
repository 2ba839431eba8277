// RayCaster (see ray_caster.hpp).
#include "bake/ray_caster.hpp"

#include "core/error.hpp"

namespace sgnlf::bake {

RayCaster::RayCaster(cl::Runtime& rt, const BakedScene& s)
    : rt_(rt), k_(rt.kernel("bake/raycast.cl", "bake_raycast")), voxel_(s.voxel_m),
      near_(s.near_m), far_(s.far_m), step_(s.step_m), stop_(s.stop_transmittance),
      brick_(s.brick) {
  s.validate();
  index_ = cl::Buffer::from(rt, s.index);
  verts_ = cl::Buffer(rt, std::max<size_t>(1, s.vertices.size()) * sizeof(BakedVertex));
  if (!s.vertices.empty()) verts_.write(s.vertices.data(), s.vertices.size() * sizeof(BakedVertex));
  mask_ = cl::Buffer::from(rt, s.cell_mask());
  bytes_ = s.bytes();
  for (int a = 0; a < 3; ++a) lo_.s[a] = float(s.origin_m[size_t(a)]), dims_.s[a] = s.dims[size_t(a)];
  lo_.s[3] = 0.0f, dims_.s[3] = 0;
}

cl::Event RayCaster::cast(const cl::Buffer& origins, const cl::Buffer& dirs, int n,
                          cl::Buffer& out) {
  require(n >= 0 && origins.bytes() >= size_t(n) * 12 && dirs.bytes() >= size_t(n) * 12 &&
              out.bytes() >= size_t(n) * kOutputs * sizeof(float),
          "RayCaster::cast: buffers too small for " + std::to_string(n) + " rays");
  k_.set_args(n, origins, dirs, lo_, voxel_, dims_, brick_, near_, far_, step_, stop_, index_,
              verts_, mask_, out);
  return k_.launch({cl::round_up(size_t(std::max(n, 1)), 64)}, {64});
}

std::vector<float> RayCaster::cast(const std::vector<float>& origins,
                                   const std::vector<float>& dirs) {
  require(origins.size() == dirs.size() && origins.size() % 3 == 0,
          "RayCaster::cast: " + std::to_string(origins.size()) + " origin and " +
              std::to_string(dirs.size()) + " direction floats");
  const int n = int(origins.size() / 3);
  if (n == 0) return {};
  if (n > cap_) {
    o_ = cl::Buffer(rt_, size_t(n) * 12), d_ = cl::Buffer(rt_, size_t(n) * 12);
    out_ = cl::Buffer(rt_, size_t(n) * kOutputs * sizeof(float));
    cap_ = n;
  }
  o_.write_vec(origins);
  d_.write_vec(dirs);
  cast(o_, d_, n, out_);
  return out_.read_vec<float>(size_t(n) * kOutputs);
}

}  // namespace sgnlf::bake
