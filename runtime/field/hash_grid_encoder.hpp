// The hash grid as a field::Encoder (LiDAR-NeRF, GeoNLF): width L·F, all parameters in the
// model's buffer, the BARF mask over its levels.
#pragma once
#include "field/encoder.hpp"
#include "field/hash_grid.hpp"

namespace sgnlf::field {

class HashGridEncoder : public Encoder {
 public:
  HashGridEncoder(cl::Runtime& rt, const HashGridConfig& cfg) : grid_(rt, cfg) {}
  int width() const override { return grid_.n_output(); }
  size_t n_params() const override { return grid_.n_params(); }
  void init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) override {
    grid_.init_params(host_params, offset, seed);
  }
  void forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
               cl::Buffer& enc) override {
    grid_.forward(params, offset, x, n, enc);
  }
  void backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                cl::Buffer* d_x) override {
    grid_.backward(params, offset, x, n, d_enc, grad, grad_offset, d_x);
  }
  int levels() const override { return grid_.config().levels; }
  void set_level_weights(const std::vector<float>& w) override { grid_.set_level_weights(w); }
  HashGrid& grid() { return grid_; }
  const HashGrid& grid() const { return grid_; }

 private:
  HashGrid grid_;
};

}  // namespace sgnlf::field
