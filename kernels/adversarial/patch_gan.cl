// Element kernels of the multi-scale PatchGAN discriminator (method.md §4.3): depth
// normalisation of the input pairs, the hinge losses' per-logit terms and gradients, and their
// sums in a fixed order (deterministic, no atomics).

// dst[dst_off + i] = factor · src[src_off + i], i < count.
__kernel void adv_scale(const int count, const float factor, __global const float* src,
                        const int src_off, __global float* dst, const int dst_off) {
  const int i = get_global_id(0);
  if (i >= count) return;
  dst[dst_off + i] = factor * src[src_off + i];
}

// Logit i (i < count) is logits[i·cs] (channel 0 of a padded conv output). mode 0, the
// discriminator's hinge loss over a batch whose first n_real logits score real pairs:
//   real: term = max(0, 1 − x), d = −w_real where 1 − x > 0;  fake: term = max(0, 1 + x),
//   d = w_fake where 1 + x > 0.
// mode 1, the generator term L_con = −mean D(fake): term = −x, d = −w_fake.
// w_real, w_fake are 1 / (logits per half · scales): means per scale, averaged over scales.
// terms[i] = w · term; d_logits gets d in channel 0 and zeros in the padding channels.
__kernel void adv_hinge_grad(const int count, const int cs, const int n_real, const int mode,
                             const float w_real, const float w_fake,
                             __global const float* logits, __global float* d_logits,
                             __global float* terms) {
  const int i = get_global_id(0);
  if (i >= count) return;
  const float x = logits[(size_t)i * cs];
  float term, d;
  if (mode == 1) {
    term = -w_fake * x;
    d = -w_fake;
  } else if (i < n_real) {
    term = w_real * fmax(0.0f, 1.0f - x);
    d = 1.0f - x > 0.0f ? -w_real : 0.0f;
  } else {
    term = w_fake * fmax(0.0f, 1.0f + x);
    d = 1.0f + x > 0.0f ? w_fake : 0.0f;
  }
  terms[i] = term;
  __global float* row = d_logits + (size_t)i * cs;
  row[0] = d;
  for (int k = 1; k < cs; ++k) row[k] = 0.0f;
}

// losses[2·slot + k] = Σ terms over [0, n_real) (k = 0) and [n_real, count) (k = 1), in index
// order. Two work-items; the terms of one scale are a few thousand values.
__kernel void adv_sum_halves(const int count, const int n_real, __global const float* terms,
                             __global float* losses, const int slot) {
  const int k = get_global_id(0);
  if (k > 1) return;
  const int begin = k == 0 ? 0 : n_real, end = k == 0 ? n_real : count;
  float s = 0.0f;
  for (int i = begin; i < end; ++i) s += terms[i];
  losses[2 * slot + k] = s;
}
