// PatchDiscriminator (patch_discriminator.hpp): composes the conv stack per scale, the hinge
// kernels (kernels/adversarial/patch_gan.cl) and the discriminator's Adam.
#include "adversarial/patch_discriminator.hpp"

#include <string>

#include "core/error.hpp"

namespace sgnlf::adversarial {
namespace {
constexpr int kPairChannels = 2;  // [D_ij or M_ij ⊙ D_j, D_j]

size_t floats_of(int n, int h, int w, int cs) { return size_t(n) * h * w * cs; }
}  // namespace

PatchDiscriminator::PatchDiscriminator(cl::Runtime& rt, const PatchDiscriminatorConfig& cfg)
    : rt_(rt), cfg_(cfg), act_(rt, cfg.slope), pool_(rt) {
  cfg_.validate();
  const int hidden = int(cfg_.channels.size());
  int c_in = kPairChannels;
  for (int l = 0; l <= hidden; ++l) {
    conv::Conv2dSpec s;
    s.c_in = c_in;
    s.c_out = l < hidden ? cfg_.channels[size_t(l)] : 1;
    s.kernel = cfg_.kernel;
    s.stride = l < hidden ? cfg_.strides[size_t(l)] : 1;
    s.pad = cfg_.padding;
    s.in_cs = l == 0 ? kPairChannels : (c_in + 15) / 16 * 16;
    convs_.push_back(std::make_unique<conv::Conv2d>(rt_, s));
    c_in = s.c_out;
  }
  offsets_.resize(size_t(cfg_.scales));
  for (int sc = 0; sc < cfg_.scales; ++sc)
    for (int l = 0; l <= hidden; ++l)
      offsets_[size_t(sc)].push_back(
          layout_
              .add("disc.s" + std::to_string(sc) + ".conv" + std::to_string(l),
                   convs_[size_t(l)]->n_params())
              .offset);
  params_ = cl::Buffer::from(rt_, initial_params());
  grad_ = cl::Buffer::from(rt_, std::vector<float>(layout_.total(), 0.0f));
  losses_ = cl::Buffer::from(rt_, std::vector<float>(size_t(4 * cfg_.scales), 0.0f));
  field::AdamConfig ac;
  ac.beta1 = cfg_.beta1;
  ac.beta2 = cfg_.beta2;
  ac.eps = cfg_.eps;
  ac.weight_decay = cfg_.weight_decay;
  adam_ = std::make_unique<field::Adam>(rt_, layout_.total(), ac);
  const std::string f = "adversarial/patch_gan.cl";
  scale_k_ = rt_.kernel(f, "adv_scale");
  hinge_k_ = rt_.kernel(f, "adv_hinge_grad");
  sum_k_ = rt_.kernel(f, "adv_sum_halves");
}

std::vector<float> PatchDiscriminator::initial_params() const {
  std::vector<float> p(layout_.total(), 0.0f);
  for (int sc = 0; sc < cfg_.scales; ++sc)
    for (size_t l = 0; l < convs_.size(); ++l)
      convs_[l]->init_params(p, offsets_[size_t(sc)][l], cfg_.seed + 1000003ull * uint64_t(sc) + l,
                             cfg_.init_std);
  return p;
}

void PatchDiscriminator::reset() {
  params_.write_vec(initial_params());
  adam_->reset();
}

std::pair<int, int> PatchDiscriminator::logit_size(int scale, int h, int w) const {
  if (scale < 0 || scale >= cfg_.scales)
    throw Error("PatchDiscriminator: scale " + std::to_string(scale) + " outside [0, " +
                std::to_string(cfg_.scales) + ")");
  const std::string image = std::to_string(h) + " x " + std::to_string(w);
  for (int s = 0; s < scale; ++s) {
    if (h < 2 || w < 2)
      throw Error("PatchDiscriminator: images of " + image + " cannot be pooled " +
                  std::to_string(scale) + " times; use fewer scales");
    h /= 2;
    w /= 2;
  }
  const std::string input = std::to_string(h) + " x " + std::to_string(w);
  for (size_t l = 0; l < convs_.size(); ++l) {
    const auto& sp = convs_[l]->spec();
    const int ho = sp.out_size(h), wo = sp.out_size(w);
    if (ho < 1 || wo < 1)
      throw Error("PatchDiscriminator: images of " + image + ": scale " +
                  std::to_string(scale) + " input " + input + " leaves " + std::to_string(h) +
                  " x " + std::to_string(w) + " before layer " + std::to_string(l) +
                  " (kernel " + std::to_string(sp.kernel) + ", stride " +
                  std::to_string(sp.stride) + ", pad " + std::to_string(sp.pad) +
                  "), too small; use fewer scales or larger images");
    h = ho;
    w = wo;
  }
  return {h, w};
}

double PatchDiscriminator::forward_macs(int n, int h, int w) const {
  double macs = 0;
  for (int sc = 0; sc < cfg_.scales; ++sc) {
    int hh = h >> sc, ww = w >> sc;
    for (const auto& c : convs_) {
      macs += c->spec().macs(n, hh, ww);
      hh = c->spec().out_size(hh);
      ww = c->spec().out_size(ww);
    }
  }
  return macs;
}

void PatchDiscriminator::ensure(int n_images, int h, int w) {
  if (n_images < 1) throw Error("PatchDiscriminator: n = " + std::to_string(n_images) + " images");
  if (h == h_ && w == w_ && n_images <= cap_) return;
  for (int sc = 0; sc < cfg_.scales; ++sc) logit_size(sc, h, w);  // throws when too small
  const int cap = std::max(n_images, h == h_ && w == w_ ? cap_ : 0);
  scales_.clear();
  scales_.resize(size_t(cfg_.scales));
  size_t max_act = 0;
  for (int sc = 0; sc < cfg_.scales; ++sc) {
    ScaleBuffers& B = scales_[size_t(sc)];
    B.h = h >> sc;
    B.w = w >> sc;
    B.x = cl::Buffer(rt_, floats_of(cap, B.h, B.w, kPairChannels) * sizeof(float));
    B.dx = cl::Buffer(rt_, floats_of(cap, B.h, B.w, kPairChannels) * sizeof(float));
    int hh = B.h, ww = B.w;
    for (size_t l = 0; l < convs_.size(); ++l) {
      const auto& sp = convs_[l]->spec();
      hh = sp.out_size(hh);
      ww = sp.out_size(ww);
      B.hs.push_back(hh);
      B.ws.push_back(ww);
      const size_t f = floats_of(cap, hh, ww, sp.out_cs());
      max_act = std::max(max_act, f);
      if (l + 1 < convs_.size()) {
        B.pre.emplace_back(rt_, f * sizeof(float));
        B.post.emplace_back(rt_, f * sizeof(float));
      } else {
        B.logits = cl::Buffer(rt_, f * sizeof(float));
        B.d_logits = cl::Buffer(rt_, f * sizeof(float));
        B.terms = cl::Buffer(rt_, size_t(cap) * hh * ww * sizeof(float));
      }
    }
  }
  for (auto& s : scratch_) s = cl::Buffer(rt_, max_act * sizeof(float));
  cap_ = cap;
  h_ = h;
  w_ = w;
}

void PatchDiscriminator::pack(const cl::Buffer& src_m, int n, int dst_image) {
  const size_t count = floats_of(n, h_, w_, kPairChannels);
  if (src_m.bytes() < count * sizeof(float))
    throw Error("PatchDiscriminator: input buffer has " + std::to_string(src_m.bytes()) +
                " bytes, needs " + std::to_string(count * sizeof(float)) + " for " +
                std::to_string(n) + " pair images of " + std::to_string(h_) + " x " +
                std::to_string(w_) + " x 2");
  scale_k_.set_args(int(count), 1.0f / cfg_.depth_scale_m, src_m, 0, scales_[0].x,
                    int(floats_of(dst_image, h_, w_, kPairChannels)));
  scale_k_.launch({cl::round_up(count, 64)}, {64});
}

void PatchDiscriminator::unpack(int src_image, int n, cl::Buffer& dst_m) {
  const size_t count = floats_of(n, h_, w_, kPairChannels);
  if (dst_m.bytes() < count * sizeof(float))
    throw Error("PatchDiscriminator: gradient buffer has " + std::to_string(dst_m.bytes()) +
                " bytes, needs " + std::to_string(count * sizeof(float)));
  // d/d(depth_m) = d/d(x) / depth_scale_m.
  scale_k_.set_args(int(count), 1.0f / cfg_.depth_scale_m, scales_[0].dx,
                    int(floats_of(src_image, h_, w_, kPairChannels)), dst_m, 0);
  scale_k_.launch({cl::round_up(count, 64)}, {64});
}

void PatchDiscriminator::run_forward(int nb) {
  const size_t hidden = convs_.size() - 1;
  for (int sc = 0; sc < cfg_.scales; ++sc) {
    ScaleBuffers& B = scales_[size_t(sc)];
    if (sc > 0) {
      const ScaleBuffers& A = scales_[size_t(sc - 1)];
      pool_.forward({nb, A.h, A.w, kPairChannels, kPairChannels, kPairChannels}, A.x, B.x);
    }
    const size_t* off = offsets_[size_t(sc)].data();
    int h = B.h, w = B.w;
    for (size_t l = 0; l <= hidden; ++l) {
      const cl::Buffer& in = l == 0 ? B.x : B.post[l - 1];
      cl::Buffer& out = l < hidden ? B.pre[l] : B.logits;
      // Hidden layers: the leaky ReLU is fused into the convolution (pre and post written).
      convs_[l]->forward(params_, off[l], in, nb, h, w, out, l < hidden ? &B.post[l] : nullptr,
                         cfg_.slope);
      h = B.hs[l];
      w = B.ws[l];
    }
  }
  last_n_ = nb;
}

void PatchDiscriminator::run_backward(int nb, int n_real, int mode, bool param_grad,
                                      bool input_grad) {
  const size_t hidden = convs_.size() - 1;
  for (int sc = cfg_.scales - 1; sc >= 0; --sc) {
    ScaleBuffers& B = scales_[size_t(sc)];
    const int per_image = B.hs[hidden] * B.ws[hidden];
    const int count = nb * per_image, real = n_real * per_image;
    const float w_real = real > 0 ? 1.0f / float(real * cfg_.scales) : 0.0f;
    const float w_fake = count > real ? 1.0f / float((count - real) * cfg_.scales) : 0.0f;
    hinge_k_.set_args(count, convs_[hidden]->spec().out_cs(), real, mode, w_real, w_fake,
                      B.logits, B.d_logits, B.terms);
    hinge_k_.launch({cl::round_up(size_t(count), 64)}, {64});
    sum_k_.set_args(count, real, B.terms, losses_, mode == 1 ? cfg_.scales + sc : sc);
    sum_k_.launch({2});
    // Through the layers, last to first; d ping-pongs between the two scratch buffers.
    const size_t* off = offsets_[size_t(sc)].data();
    const cl::Buffer* d_out = &B.d_logits;
    int cur = 0;
    for (size_t l = hidden + 1; l-- > 0;) {
      const int h = l == 0 ? B.h : B.hs[l - 1], w = l == 0 ? B.w : B.ws[l - 1];
      const cl::Buffer& in = l == 0 ? B.x : B.post[l - 1];
      cl::Buffer* d_in = l == 0 ? (input_grad ? &B.dx : nullptr) : &scratch_[cur];
      convs_[l]->backward(params_, off[l], in, nb, h, w, *d_out,
                          param_grad ? &grad_ : nullptr, off[l], d_in);
      if (l == 0) break;
      // Through the leaky ReLU of layer l − 1, in place.
      act_.backward(B.pre[l - 1], scratch_[cur],
                    floats_of(nb, h, w, convs_[l - 1]->spec().out_cs()), scratch_[cur]);
      d_out = &scratch_[cur];
      cur = 1 - cur;
    }
  }
  if (!input_grad) return;
  // Input pyramid, coarse to fine: dx_{s−1} += pool'ᵀ dx_s.
  for (int sc = cfg_.scales - 1; sc > 0; --sc) {
    const ScaleBuffers& A = scales_[size_t(sc - 1)];
    pool_.backward({nb, A.h, A.w, kPairChannels, kPairChannels, kPairChannels},
                   scales_[size_t(sc)].dx, scales_[size_t(sc - 1)].dx, true);
  }
}

void PatchDiscriminator::forward(const cl::Buffer& images_m, int n, int h, int w) {
  ensure(n, h, w);
  pack(images_m, n, 0);
  run_forward(n);
}

std::vector<float> PatchDiscriminator::read_logits(int scale) const {
  if (last_n_ == 0) throw Error("PatchDiscriminator::read_logits: no forward pass yet");
  logit_size(scale, h_, w_);
  const ScaleBuffers& B = scales_[size_t(scale)];
  const size_t last = convs_.size() - 1, cs = size_t(convs_[last]->spec().out_cs());
  const size_t count = size_t(last_n_) * B.hs[last] * B.ws[last];
  const auto raw = B.logits.read_vec<float>(count * cs);
  std::vector<float> out(count);
  for (size_t i = 0; i < count; ++i) out[i] = raw[i * cs];
  return out;
}

void PatchDiscriminator::discriminator_grad(const cl::Buffer& real_m, const cl::Buffer& fake_m,
                                            int n, int h, int w, cl::Buffer* d_real_m,
                                            cl::Buffer* d_fake_m) {
  ensure(2 * n, h, w);
  pack(real_m, n, 0);
  pack(fake_m, n, n);
  run_forward(2 * n);
  const bool input_grad = d_real_m || d_fake_m;
  run_backward(2 * n, n, 0, true, input_grad);
  if (d_real_m) unpack(0, n, *d_real_m);
  if (d_fake_m) unpack(n, n, *d_fake_m);
}

void PatchDiscriminator::step(const cl::Buffer& real_m, const cl::Buffer& fake_m, int n, int h,
                              int w) {
  discriminator_grad(real_m, fake_m, n, h, w);
  adam_->begin_step();
  adam_->update(params_, grad_, 0, layout_.total(), cfg_.lr);
}

void PatchDiscriminator::generator_grad(const cl::Buffer& fake_m, int n, int h, int w,
                                        cl::Buffer& d_fake_m) {
  ensure(n, h, w);
  pack(fake_m, n, 0);
  run_forward(n);
  run_backward(n, 0, 1, false, true);
  unpack(0, n, d_fake_m);
}

HingeLosses PatchDiscriminator::read_losses() const {
  const auto v = losses_.read_all<float>();
  HingeLosses l;
  for (int sc = 0; sc < cfg_.scales; ++sc) {
    l.d_real += v[size_t(2 * sc)];
    l.d_fake += v[size_t(2 * sc + 1)];
    l.con += v[size_t(2 * (cfg_.scales + sc) + 1)];  // mode 1 sums all logits in the second half
  }
  return l;
}

}  // namespace sgnlf::adversarial
