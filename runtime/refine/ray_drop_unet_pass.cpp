// RayDropUNet's passes (ray_drop_unet.hpp): input packing, forward, BCE, backward, Adam.
// Backward order: the up stages from level 0 to depth − 1 (each leaves the skip's gradient in
// g_e[l] and passes the rest through up2ᵀ), then the down stages from depth to 1 (each adds
// maxpool2ᵀ of its input gradient onto g_e[l − 1]), then the 1×1 in-conv.
#include <string>

#include "core/error.hpp"
#include "refine/ray_drop_unet.hpp"

namespace sgnlf::refine {
namespace {
size_t floats(int n, int h, int w, int c) { return size_t(n) * h * w * c; }
}  // namespace

void RayDropUNet::pack(const cl::Buffer& inputs, int n, const cl::Buffer& boxes, int box_off,
                       int n_boxes) {
  const conv::BoxMaskShape s{n, h_, w_, kInputChannels, kInputChannels, kInputChannels};
  mask_.run(s, scale_, boxes, box_off, n_boxes, inputs, x_);
}

void RayDropUNet::block_forward(Block& b, const cl::Buffer& in, int n, int h, int w) {
  b.a->forward(params_, b.off_a, in, n, h, w, b.pre_a, &b.post_a, cfg_.slope);
  b.b->forward(params_, b.off_b, b.post_a, n, h, w, b.pre_b, &b.post_b, cfg_.slope);
}

void RayDropUNet::run_forward(int n) {
  inc_->forward(params_, off_in_, x_, n, h_, w_, e0_pre_, &e0_post_, cfg_.slope);
  for (int l = 1; l <= cfg_.depth; ++l) {
    const Level& up = levels_[size_t(l - 1)];
    Level& L = levels_[size_t(l)];
    const int c = widths_[size_t(l - 1)];
    pool_.forward({n, up.h, up.w, c, c, c}, e(l - 1), L.pooled);
    block_forward(enc_[size_t(l)], L.pooled, n, L.h, L.w);
  }
  for (int l = cfg_.depth - 1; l >= 0; --l) {
    Level& L = levels_[size_t(l)];
    const Level& below = levels_[size_t(l + 1)];
    const int skip = widths_[size_t(l)], upc = up_width(l), cat = skip + upc;
    copy_.run({n * L.h * L.w, skip, skip, 0, cat, 0}, e(l), L.cat, false);
    up_.forward({n, below.h, below.w, upc, upc, L.h, L.w, cat, skip}, d(l + 1), L.cat);
    block_forward(dec_[size_t(l)], L.cat, n, L.h, L.w);
  }
  outc_->forward(params_, off_out_, d(0), n, h_, w_, logits_);
}

void RayDropUNet::block_backward(Block& b, const cl::Buffer& in, int n, int h, int w,
                                 cl::Buffer& dy, cl::Buffer& d_in) {
  cl::Buffer& mid = scratch_[1];
  act_.backward(b.pre_b, dy, floats(n, h, w, b.b->spec().c_out), dy);
  b.b->backward(params_, b.off_b, b.post_a, n, h, w, dy, &grad_, b.off_b, &mid);
  act_.backward(b.pre_a, mid, floats(n, h, w, b.a->spec().c_out), mid);
  b.a->backward(params_, b.off_a, in, n, h, w, mid, &grad_, b.off_a, &d_in);
}

void RayDropUNet::run_backward(int n) {
  // dL/d d_0 in scratch 0; scratch 1 holds the middle activations' gradients, scratch 2 the
  // blocks' input gradients.
  outc_->backward(params_, off_out_, d(0), n, h_, w_, d_logits_, &grad_, off_out_, &scratch_[0]);
  for (int l = 0; l < cfg_.depth; ++l) {
    Level& L = levels_[size_t(l)];
    Level& below = levels_[size_t(l + 1)];
    const int skip = widths_[size_t(l)], upc = up_width(l), cat = skip + upc;
    block_backward(dec_[size_t(l)], L.cat, n, L.h, L.w, scratch_[0], scratch_[2]);
    copy_.run({n * L.h * L.w, skip, cat, 0, skip, 0}, scratch_[2], L.g_e, false);
    cl::Buffer& d_below = l + 1 == cfg_.depth ? below.g_e : scratch_[0];
    up_.backward({n, below.h, below.w, upc, upc, L.h, L.w, cat, skip}, scratch_[2], d_below, false);
  }
  for (int l = cfg_.depth; l >= 1; --l) {
    Level& L = levels_[size_t(l)];
    Level& above = levels_[size_t(l - 1)];
    block_backward(enc_[size_t(l)], L.pooled, n, L.h, L.w, L.g_e, scratch_[2]);
    const int c = widths_[size_t(l - 1)];
    pool_.backward({n, above.h, above.w, c, c, c}, e(l - 1), scratch_[2], above.g_e, true);
  }
  Level& top = levels_[0];
  act_.backward(e0_pre_, top.g_e, floats(n, h_, w_, widths_[0]), top.g_e);
  inc_->backward(params_, off_in_, x_, n, h_, w_, top.g_e, &grad_, off_in_, nullptr);
}

void RayDropUNet::forward(const cl::Buffer& inputs, int n, int h, int w, cl::Buffer& probs) {
  ensure(n, h, w);
  pack(inputs, n, no_boxes_, 0, 0);
  run_forward(n);
  bce_.sigmoid(logits_, n * h * w, 16, probs);
}

double RayDropUNet::loss(const cl::Buffer& inputs, const cl::Buffer& masks, int n, int h, int w) {
  ensure(n, h, w);
  pack(inputs, n, no_boxes_, 0, 0);
  run_forward(n);
  bce_.loss_grad(logits_, n * h * w, 16, masks, d_logits_, eval_loss_, 0);
  return double(eval_loss_.read_vec<float>(1)[0]);
}

void RayDropUNet::step(const cl::Buffer& inputs, const cl::Buffer& masks, int n, int h, int w,
                       const cl::Buffer& boxes, int box_off, int n_boxes, float lr,
                       cl::Buffer& losses, int slot) {
  ensure(n, h, w);
  pack(inputs, n, boxes, box_off, n_boxes);
  run_forward(n);
  bce_.loss_grad(logits_, n * h * w, 16, masks, d_logits_, losses, slot);
  run_backward(n);
  adam_->begin_step();
  adam_->update(params_, grad_, 0, layout_.total(), lr);
}

}  // namespace sgnlf::refine
