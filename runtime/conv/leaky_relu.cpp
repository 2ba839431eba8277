// LeakyRelu host launcher (kernels/conv/activation.cl).
#include "conv/leaky_relu.hpp"

#include <string>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::conv {
namespace {
void check(const cl::Buffer& b, size_t count, const char* what) {
  if (b.bytes() < count * sizeof(float))
    throw Error(std::string("LeakyRelu: buffer '") + what + "' has " + std::to_string(b.bytes()) +
                " bytes, needs " + std::to_string(count * sizeof(float)));
  if (count > size_t(1) << 30) throw Error("LeakyRelu: count " + std::to_string(count) + " above 2^30");
}
}  // namespace

LeakyRelu::LeakyRelu(cl::Runtime& rt, float slope) : slope_(slope) {
  check_range("leaky_relu", "slope", slope, 0.0f, 1.0f);
  fwd_ = rt.kernel("conv/activation.cl", "conv_leaky_relu_fwd");
  bwd_ = rt.kernel("conv/activation.cl", "conv_leaky_relu_bwd");
}

void LeakyRelu::forward(const cl::Buffer& x, size_t count, cl::Buffer& y) {
  check(x, count, "x");
  check(y, count, "y");
  if (count == 0) return;
  fwd_.set_args(int(count), slope_, x, y);
  fwd_.launch({cl::round_up((count + 15) / 16, 64)}, {64});
}

void LeakyRelu::backward(const cl::Buffer& x, const cl::Buffer& dy, size_t count,
                         cl::Buffer& dx) {
  check(x, count, "x");
  check(dy, count, "dy");
  check(dx, count, "dx");
  if (count == 0) return;
  bwd_.set_args(int(count), slope_, x, dy, dx);
  bwd_.launch({cl::round_up((count + 15) / 16, 64)}, {64});
}

}  // namespace sgnlf::conv
