// BceWithLogits host launcher (kernels/conv/bce.cl).
#include "conv/bce_loss.hpp"

#include <algorithm>
#include <string>

#include "conv/buffer_check.hpp"

namespace sgnlf::conv {
namespace {
constexpr int kMaxChunks = 1024;  // first-phase work-items at most
constexpr int kMinChunk = 256;    // pixels per work-item at least

void check_count(int count, int cs, const char* where) {
  if (count < 1 || cs < 1)
    throw Error(std::string("BceWithLogits::") + where + ": count = " + std::to_string(count) +
                ", cs = " + std::to_string(cs) + " (both must be >= 1)");
}
}  // namespace

BceWithLogits::BceWithLogits(cl::Runtime& rt) : rt_(rt) {
  partial_k_ = rt.kernel("conv/bce.cl", "conv_bce_partial");
  sum_k_ = rt.kernel("conv/bce.cl", "conv_bce_sum");
  sigmoid_k_ = rt.kernel("conv/bce.cl", "conv_sigmoid_fwd");
}

int BceWithLogits::chunk_size(int count) {
  return std::max(kMinChunk, (count + kMaxChunks - 1) / kMaxChunks);
}

int BceWithLogits::chunks(int count) {
  const int chunk = chunk_size(count);
  return (count + chunk - 1) / chunk;
}

void BceWithLogits::loss_grad(const cl::Buffer& logits, int count, int cs,
                              const cl::Buffer& target, cl::Buffer& d_logits,
                              cl::Buffer& losses, int slot) {
  check_count(count, cs, "loss_grad");
  check_floats(logits, size_t(count) * cs, "BceWithLogits", "logits");
  check_floats(target, size_t(count), "BceWithLogits", "target");
  check_floats(d_logits, size_t(count) * cs, "BceWithLogits", "d_logits");
  if (slot < 0) throw Error("BceWithLogits: slot " + std::to_string(slot) + " is negative");
  check_floats(losses, size_t(slot) + 1, "BceWithLogits", "losses");
  const int n = chunks(count);
  if (partial_.bytes() < size_t(n) * sizeof(float))
    partial_ = cl::Buffer(rt_, size_t(kMaxChunks) * sizeof(float));
  const float inv = 1.0f / float(count);
  partial_k_.set_args(count, chunk_size(count), cs, inv, logits, target, d_logits, partial_);
  partial_k_.launch({cl::round_up(size_t(n), 64)}, {64});
  sum_k_.set_args(n, inv, partial_, losses, slot);
  sum_k_.launch({1});
}

void BceWithLogits::sigmoid(const cl::Buffer& logits, int count, int cs, cl::Buffer& probs) {
  check_count(count, cs, "sigmoid");
  check_floats(logits, size_t(count) * cs, "BceWithLogits", "logits");
  check_floats(probs, size_t(count), "BceWithLogits", "probs");
  sigmoid_k_.set_args(count, cs, logits, probs);
  sigmoid_k_.launch({cl::round_up(size_t(count), 64)}, {64});
}

}  // namespace sgnlf::conv
