// Sigmoid + binary cross-entropy on one-channel logits (channel 0 of a padded conv output, as
// the U-Net's last 1×1 convolution writes them): LiDAR4D's ray-drop refinement loss
// (nn.BCELoss on sigmoid outputs, method.md §2), in the stable logit form
//   ℓ(z, y) = max(z, 0) − z·y + log(1 + exp(−|z|)),   dℓ/dz = σ(z) − y,
// averaged over the count pixels. Deterministic: each of the n_chunks work-items sums a fixed
// chunk of pixels in index order, and one work-item sums the chunks in order (no atomics).

inline float conv_sigmoid1(const float z) { return 1.0f / (1.0f + exp(-z)); }

// Pixels [g·chunk, min(count, (g+1)·chunk)) of work-item g: d_logits (channel 0 = (σ(z) − y) ·
// inv_count, padding channels 0) and partial[g] = Σ ℓ in index order.
__kernel void conv_bce_partial(const int count, const int chunk, const int cs,
                               const float inv_count, __global const float* logits,
                               __global const float* target, __global float* d_logits,
                               __global float* partial) {
  const int g = get_global_id(0);
  const int begin = g * chunk;
  if (begin >= count) return;
  const int end = min(count, begin + chunk);
  float s = 0.0f;
  for (int i = begin; i < end; ++i) {
    const float z = logits[(size_t)i * cs], y = target[i];
    s += fmax(z, 0.0f) - z * y + log1p(exp(-fabs(z)));
    __global float* row = d_logits + (size_t)i * cs;
    row[0] = (conv_sigmoid1(z) - y) * inv_count;
    for (int k = 1; k < cs; ++k) row[k] = 0.0f;
  }
  partial[g] = s;
}

// losses[slot] = inv_count · Σ_g partial[g], in order. One work-item.
__kernel void conv_bce_sum(const int n_chunks, const float inv_count,
                           __global const float* partial, __global float* losses,
                           const int slot) {
  if (get_global_id(0) != 0) return;
  float s = 0.0f;
  for (int g = 0; g < n_chunks; ++g) s += partial[g];
  losses[slot] = s * inv_count;
}

// probs[i] = σ(logits[i·cs]), i < count (inference output, compact).
__kernel void conv_sigmoid_fwd(const int count, const int cs, __global const float* logits,
                               __global float* probs) {
  const int i = get_global_id(0);
  if (i >= count) return;
  probs[i] = conv_sigmoid1(logits[(size_t)i * cs]);
}
