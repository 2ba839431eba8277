// RayDropUNet (ray_drop_unet.hpp): the layers, the parameter layout and initialisation, the
// buffers per image size. The passes are in ray_drop_unet_pass.cpp.
#include "refine/ray_drop_unet.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace sgnlf::refine {
namespace {
conv::Conv2dSpec spec(int c_in, int c_out, int kernel) {
  conv::Conv2dSpec s;
  s.c_in = c_in;
  s.c_out = c_out;
  s.kernel = kernel;
  s.stride = 1;
  s.pad = kernel / 2;
  s.in_cs = c_in;  // every input is a conv-stack tensor of exactly c_in channels (or the 3 inputs)
  return s;
}
cl::Buffer zeroed(cl::Runtime& rt, size_t floats) {
  cl::Buffer b(rt, std::max<size_t>(floats, 1) * sizeof(float));
  b.fill_zero();
  return b;
}
}  // namespace

RayDropUNet::RayDropUNet(cl::Runtime& rt, const RayDropUNetConfig& cfg)
    : rt_(rt), cfg_(cfg), act_(rt, cfg.slope), pool_(rt), up_(rt), copy_(rt), bce_(rt),
      mask_(rt) {
  cfg_.validate();
  const int depth = cfg_.depth;
  for (int l = 0; l <= depth; ++l) widths_.push_back(cfg_.channels << std::min(l, depth - 1));
  inc_ = std::make_unique<conv::Conv2d>(rt_, spec(kInputChannels, widths_[0], 1));
  off_in_ = layout_.add("unet.in", inc_->n_params()).offset;
  enc_.resize(size_t(depth) + 1);
  for (int l = 1; l <= depth; ++l) {
    Block& b = enc_[size_t(l)];
    b.a = std::make_unique<conv::Conv2d>(rt_, spec(widths_[size_t(l - 1)], widths_[size_t(l)], 3));
    b.b = std::make_unique<conv::Conv2d>(rt_, spec(widths_[size_t(l)], widths_[size_t(l)], 3));
    b.off_a = layout_.add("unet.down" + std::to_string(l) + ".a", b.a->n_params()).offset;
    b.off_b = layout_.add("unet.down" + std::to_string(l) + ".b", b.b->n_params()).offset;
  }
  dec_.resize(size_t(depth));
  for (int l = depth - 1; l >= 0; --l) {
    Block& b = dec_[size_t(l)];
    const int cat = widths_[size_t(l)] + up_width(l);
    b.a = std::make_unique<conv::Conv2d>(rt_, spec(cat, cat, 3));
    b.b = std::make_unique<conv::Conv2d>(rt_, spec(cat, dec_width(l), 3));
    b.off_a = layout_.add("unet.up" + std::to_string(l) + ".a", b.a->n_params()).offset;
    b.off_b = layout_.add("unet.up" + std::to_string(l) + ".b", b.b->n_params()).offset;
  }
  outc_ = std::make_unique<conv::Conv2d>(rt_, spec(widths_[0], 1, 1));
  off_out_ = layout_.add("unet.out", outc_->n_params()).offset;

  params_ = cl::Buffer::from(rt_, initial_params());
  grad_ = zeroed(rt_, layout_.total());
  field::AdamConfig ac;
  ac.beta1 = cfg_.beta1;
  ac.beta2 = cfg_.beta2;
  ac.eps = cfg_.eps;
  ac.weight_decay = cfg_.weight_decay;
  adam_ = std::make_unique<field::Adam>(rt_, layout_.total(), ac);
  scale_ = cl::Buffer::from(rt_, std::vector<float>{1.0f, 1.0f, 1.0f / cfg_.depth_scale_m});
  no_boxes_ = cl::Buffer::from(rt_, std::vector<int>(4, 0));
  eval_loss_ = zeroed(rt_, 1);
}

int RayDropUNet::dec_width(int l) const { return widths_[size_t(std::max(l - 1, 0))]; }
int RayDropUNet::up_width(int l) const {
  return l + 1 == cfg_.depth ? widths_[size_t(cfg_.depth)] : dec_width(l + 1);
}

std::vector<float> RayDropUNet::initial_params() const {
  std::vector<float> p(layout_.total(), 0.0f);
  // He initialisation for the convs followed by an activation, 1/√fan_in for the logit conv;
  // one seed per layer in the layout's order.
  const double he = 2.0 / (1.0 + double(cfg_.slope) * cfg_.slope);
  uint64_t layer = 0;
  auto init = [&](const conv::Conv2d& c, size_t off, double gain2) {
    const auto& s = c.spec();
    const double fan_in = double(s.kernel) * s.kernel * s.c_in;
    c.init_params(p, off, cfg_.seed + 1000003ull * layer++,
                  float(cfg_.init_gain * std::sqrt(gain2 / fan_in)));
  };
  init(*inc_, off_in_, he);
  for (int l = 1; l <= cfg_.depth; ++l) {
    init(*enc_[size_t(l)].a, enc_[size_t(l)].off_a, he);
    init(*enc_[size_t(l)].b, enc_[size_t(l)].off_b, he);
  }
  for (int l = cfg_.depth - 1; l >= 0; --l) {
    init(*dec_[size_t(l)].a, dec_[size_t(l)].off_a, he);
    init(*dec_[size_t(l)].b, dec_[size_t(l)].off_b, he);
  }
  init(*outc_, off_out_, 1.0);
  return p;
}

void RayDropUNet::reset() {
  params_.write_vec(initial_params());
  adam_->reset();
}

void RayDropUNet::check_size(int h, int w) const {
  const int need = 1 << cfg_.depth;
  if (h < need || w < need)
    throw Error("RayDropUNet: images of " + std::to_string(h) + " x " + std::to_string(w) +
                " cannot be pooled " + std::to_string(cfg_.depth) + " times (depth = " +
                std::to_string(cfg_.depth) + " needs at least " + std::to_string(need) + " x " +
                std::to_string(need) + ")");
}

double RayDropUNet::forward_macs(int n, int h, int w) const {
  check_size(h, w);
  double macs = inc_->spec().macs(n, h, w) + outc_->spec().macs(n, h, w);
  for (int l = 0; l <= cfg_.depth; ++l) {
    const Block* enc = l > 0 ? &enc_[size_t(l)] : nullptr;
    const Block* dec = l < cfg_.depth ? &dec_[size_t(l)] : nullptr;
    for (const Block* b : {enc, dec})
      if (b) macs += b->a->spec().macs(n, h, w) + b->b->spec().macs(n, h, w);
    h /= 2;
    w /= 2;
  }
  return macs;
}

const cl::Buffer& RayDropUNet::e(int l) const { return l == 0 ? e0_post_ : enc_[size_t(l)].post_b; }
const cl::Buffer& RayDropUNet::d(int l) const {
  return l == cfg_.depth ? e(l) : dec_[size_t(l)].post_b;
}

void RayDropUNet::ensure(int n, int h, int w) {
  if (n < 1) throw Error("RayDropUNet: n = " + std::to_string(n) + " images");
  check_size(h, w);
  if (h == h_ && w == w_ && n <= cap_) return;
  const int cap = std::max(n, h == h_ && w == w_ ? cap_ : 0);
  const size_t n0 = size_t(cap) * h * w;
  x_ = zeroed(rt_, n0 * kInputChannels);
  e0_pre_ = zeroed(rt_, n0 * widths_[0]);
  e0_post_ = zeroed(rt_, n0 * widths_[0]);
  logits_ = zeroed(rt_, n0 * 16);
  d_logits_ = zeroed(rt_, n0 * 16);
  levels_.clear();
  levels_.resize(size_t(cfg_.depth) + 1);
  size_t widest = n0 * 16;
  int hh = h, ww = w;
  for (int l = 0; l <= cfg_.depth; ++l, hh /= 2, ww /= 2) {
    Level& L = levels_[size_t(l)];
    L.h = hh;
    L.w = ww;
    const size_t pix = size_t(cap) * hh * ww;
    L.g_e = zeroed(rt_, pix * widths_[size_t(l)]);
    auto alloc = [&](Block& b, int c_mid, int c_out) {
      for (cl::Buffer* buf : {&b.pre_a, &b.post_a}) *buf = zeroed(rt_, pix * c_mid);
      for (cl::Buffer* buf : {&b.pre_b, &b.post_b}) *buf = zeroed(rt_, pix * c_out);
      widest = std::max(widest, pix * std::max(c_mid, c_out));
    };
    if (l > 0) {
      L.pooled = zeroed(rt_, pix * widths_[size_t(l - 1)]);
      alloc(enc_[size_t(l)], widths_[size_t(l)], widths_[size_t(l)]);
    }
    if (l < cfg_.depth) {
      const int cat = widths_[size_t(l)] + up_width(l);
      L.cat = zeroed(rt_, pix * cat);
      alloc(dec_[size_t(l)], cat, dec_width(l));
    }
  }
  for (auto& s : scratch_) s = zeroed(rt_, widest);
  cap_ = cap;
  h_ = h;
  w_ = w;
}

}  // namespace sgnlf::refine
