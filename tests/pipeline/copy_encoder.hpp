// A field::Encoder for launcher tests: the encoding of a point is its position (width 3), so
// that a test can tell which rows a launcher encoded. Forward only.
#pragma once
#include <stdexcept>

#include "field/encoder.hpp"

namespace sgnlf::test {

class CopyEncoder : public field::Encoder {
 public:
  int width() const override { return 3; }
  size_t n_params() const override { return 0; }
  void init_params(std::vector<float>&, size_t, uint64_t) override {}
  void forward(const cl::Buffer&, size_t, const cl::Buffer& x, int n, cl::Buffer& enc) override {
    enc.copy_from(x, size_t(n) * 3 * sizeof(float));
    ++calls;
    rows += n;
  }
  void backward(const cl::Buffer&, size_t, const cl::Buffer&, int, const cl::Buffer&, cl::Buffer&,
                size_t, cl::Buffer*) override {
    throw std::logic_error("CopyEncoder has no backward");
  }
  int levels() const override { return 0; }
  void set_level_weights(const std::vector<float>&) override {}

  int calls = 0;  // forward() calls and the rows they encoded
  long rows = 0;
};

}  // namespace sgnlf::test
