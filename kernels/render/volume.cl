// Volume rendering along LiDAR rays (method.md §0), forward and backward, one work-item per
// ray, its S ray-major samples taken in chunks of 8 (float8 math: PoCL vectorises these, not
// loops over scalars) plus a scalar tail when S % 8 != 0. Fixed order: deterministic.
//   sigma_i = trunc_exp(h0_i)      forward exp(h0) (h0 capped at 80 only so that sigma stays
//                                  finite in float), backward exp(clamp(h0, -15, 15))
//   delta_i = t_{i+1} - t_i, and delta_{S-1} = last_delta (the host passes the uniform bin
//            width (far - near) / S_uniform, as torch-ngp / LiDAR-NeRF do)
//   alpha_i = 1 - exp(-sigma_i delta_i),  w_i = alpha_i prod_{j<i} (1 - alpha_j)
//   depth = sum w_i t_i (not normalised), prob = sum w_i sigmoid(a_i), inten = sum w_i sigmoid(b_i)
// head is N x 2 (return-probability logit a, intensity logit b); out is n_rays x 3
// (depth, prob, intensity). Host references: tests/render/render_reference.hpp.

inline float render_sigmoid(float v) { return 1.0f / (1.0f + exp(-v)); }

// delta of the scalar sample i (global index s).
inline float render_delta(__global const float* t, int s, int i, int n_samples, float last_delta) {
  return i + 1 < n_samples ? t[s + 1] - t[s] : last_delta;
}

// deltas of the chunk of 8 samples starting at sample c (global index s); tt = their t.
inline float8 render_delta8(__global const float* t, int s, int c, int n_samples, float last_delta,
                            float8 tt) {
  const float next = c + 8 < n_samples ? t[s + 8] : 0.0f;
  float8 delta = (float8)(tt.s1, tt.s2, tt.s3, tt.s4, tt.s5, tt.s6, tt.s7, next) - tt;
  if (c + 8 >= n_samples) delta.s7 = last_delta;
  return delta;
}

// exp(-sigma delta) of a chunk.
inline float8 render_decay8(__global const float* h0, int s, float8 delta) {
  return exp(-exp(fmin(vload8(0, h0 + s), 80.0f)) * delta);
}

// Weights of a chunk from the transmittance before it; advances *trans past it.
inline float8 render_weights8(float8 e, float* trans) {
  float8 T;
  T.s0 = *trans;
  T.s1 = T.s0 * e.s0;
  T.s2 = T.s1 * e.s1;
  T.s3 = T.s2 * e.s2;
  T.s4 = T.s3 * e.s3;
  T.s5 = T.s4 * e.s4;
  T.s6 = T.s5 * e.s5;
  T.s7 = T.s6 * e.s6;
  *trans = T.s7 * e.s7;
  return T * (1.0f - e);
}

inline float render_hsum8(float8 v) {
  const float4 a = v.lo + v.hi;
  return (a.x + a.y) + (a.z + a.w);
}

__kernel void render_volume_fwd(const int n_rays, const int n_samples, const float last_delta,
                                __global const float* t, __global const float* h0,
                                __global const float* head, __global float* out,
                                __global float* weights) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int base = r * n_samples, n_full = n_samples & ~7;
  float trans = 1.0f;
  float8 acc_d = 0.0f, acc_p = 0.0f, acc_i = 0.0f;
  for (int c = 0; c < n_full; c += 8) {
    const int s = base + c;
    const float8 tt = vload8(0, t + s);
    const float8 e = render_decay8(h0, s, render_delta8(t, s, c, n_samples, last_delta, tt));
    const float8 w = render_weights8(e, &trans);
    const float16 hd = vload16(0, head + 2 * s);
    acc_d += w * tt;
    acc_p += w / (1.0f + exp(-hd.even));
    acc_i += w / (1.0f + exp(-hd.odd));
    vstore8(w, 0, weights + s);
  }
  float depth = render_hsum8(acc_d), prob = render_hsum8(acc_p), inten = render_hsum8(acc_i);
  for (int i = n_full; i < n_samples; ++i) {
    const int s = base + i;
    const float e = exp(-exp(fmin(h0[s], 80.0f)) * render_delta(t, s, i, n_samples, last_delta));
    const float w = trans * (1.0f - e);
    depth += w * t[s];
    prob += w * render_sigmoid(head[2 * s]);
    inten += w * render_sigmoid(head[2 * s + 1]);
    weights[s] = w;
    trans *= e;
  }
  out[3 * r + 0] = depth;
  out[3 * r + 1] = prob;
  out[3 * r + 2] = inten;
}

// Weights only (no head): the coarse pass of importance sampling. Same arithmetic as the
// forward, so the weights are bit-identical to the forward's.
__kernel void render_volume_weights(const int n_rays, const int n_samples, const float last_delta,
                                    __global const float* t, __global const float* h0,
                                    __global float* weights) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int base = r * n_samples, n_full = n_samples & ~7;
  float trans = 1.0f;
  for (int c = 0; c < n_full; c += 8) {
    const int s = base + c;
    const float8 tt = vload8(0, t + s);
    const float8 e = render_decay8(h0, s, render_delta8(t, s, c, n_samples, last_delta, tt));
    vstore8(render_weights8(e, &trans), 0, weights + s);
  }
  for (int i = n_full; i < n_samples; ++i) {
    const int s = base + i;
    const float e = exp(-exp(fmin(h0[s], 80.0f)) * render_delta(t, s, i, n_samples, last_delta));
    weights[s] = trans * (1.0f - e);
    trans *= e;
  }
}

// Backward. With C = sum_k w_k c_k, T_{i+1} = T_i exp(-tau_i) and w_i = T_i - T_{i+1}:
//   dC/dtau_i = T_{i+1} c_i - sum_{k>i} w_k c_k
//   dL/dh0_i  = dL/dtau_i * delta_i * exp(clamp(h0_i, -15, 15))
//   dL/dhead  = g_c * w_i * s (1 - s) for the two sigmoid channels.
// The suffix sums and T_{i+1} = T_S + sum_{k>i} w_k are accumulated in a reverse pass over the
// forward's weights: sums of non-negative terms, so late samples of opaque rays keep their
// relative accuracy (the usual C - prefix form cancels catastrophically there). T_S, the
// final transmittance, is a forward product over exp(-tau). Reverse order: scalar tail, then
// the chunks of 8 from the last to the first.
__kernel void render_volume_bwd(const int n_rays, const int n_samples, const float last_delta,
                                __global const float* t, __global const float* h0,
                                __global const float* head, __global const float* weights,
                                __global const float* grad_out, __global float* grad_h0,
                                __global float* grad_head) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int base = r * n_samples, n_full = n_samples & ~7;
  const float g_d = grad_out[3 * r], g_p = grad_out[3 * r + 1], g_i = grad_out[3 * r + 2];
  float trans = 1.0f;
  for (int c = 0; c < n_full; c += 8) {
    const int s = base + c;
    const float8 e =
        render_decay8(h0, s, render_delta8(t, s, c, n_samples, last_delta, vload8(0, t + s)));
    trans *= ((e.s0 * e.s1) * (e.s2 * e.s3)) * ((e.s4 * e.s5) * (e.s6 * e.s7));
  }
  for (int i = n_full; i < n_samples; ++i) {
    const int s = base + i;
    trans *= exp(-exp(fmin(h0[s], 80.0f)) * render_delta(t, s, i, n_samples, last_delta));
  }
  float suffix = 0.0f;  // sum_{k>i} w_k (g . c_k); trans = T_{i+1}
  for (int i = n_samples - 1; i >= n_full; --i) {
    const int s = base + i;
    const float w = weights[s];
    const float sp = render_sigmoid(head[2 * s]), si = render_sigmoid(head[2 * s + 1]);
    const float gc = g_d * t[s] + g_p * sp + g_i * si;
    grad_h0[s] = (trans * gc - suffix) * render_delta(t, s, i, n_samples, last_delta) *
                 exp(clamp(h0[s], -15.0f, 15.0f));
    grad_head[2 * s] = g_p * w * sp * (1.0f - sp);
    grad_head[2 * s + 1] = g_i * w * si * (1.0f - si);
    suffix += w * gc;
    trans += w;
  }
  for (int c = n_full - 8; c >= 0; c -= 8) {
    const int s = base + c;
    const float8 tt = vload8(0, t + s), w = vload8(0, weights + s);
    const float16 hd = vload16(0, head + 2 * s);
    const float8 sp = 1.0f / (1.0f + exp(-hd.even)), si = 1.0f / (1.0f + exp(-hd.odd));
    const float8 gc = g_d * tt + g_p * sp + g_i * si;
    const float8 wgc = w * gc;
    float8 tn, suf;  // T_{i+1} and the suffix sum after each lane, filled in reverse
    tn.s7 = trans;
    suf.s7 = suffix;
    suffix += wgc.s7;
    trans += w.s7;
    tn.s6 = trans;
    suf.s6 = suffix;
    suffix += wgc.s6;
    trans += w.s6;
    tn.s5 = trans;
    suf.s5 = suffix;
    suffix += wgc.s5;
    trans += w.s5;
    tn.s4 = trans;
    suf.s4 = suffix;
    suffix += wgc.s4;
    trans += w.s4;
    tn.s3 = trans;
    suf.s3 = suffix;
    suffix += wgc.s3;
    trans += w.s3;
    tn.s2 = trans;
    suf.s2 = suffix;
    suffix += wgc.s2;
    trans += w.s2;
    tn.s1 = trans;
    suf.s1 = suffix;
    suffix += wgc.s1;
    trans += w.s1;
    tn.s0 = trans;
    suf.s0 = suffix;
    suffix += wgc.s0;
    trans += w.s0;
    const float8 delta = render_delta8(t, s, c, n_samples, last_delta, tt);
    vstore8((tn * gc - suf) * delta * exp(clamp(vload8(0, h0 + s), -15.0f, 15.0f)), 0, grad_h0 + s);
    float16 gh;
    gh.even = g_p * w * sp * (1.0f - sp);
    gh.odd = g_i * w * si * (1.0f - si);
    vstore16(gh, 0, grad_head + 2 * s);
  }
}

// Median depth (evaluation only; not differentiable, no backward): per ray, the range at which
// the transmittance falls to 1/2. With the density constant over each sample's interval
// [t_i, t_i + delta_i) (the quadrature of render_volume_fwd), the crossing lies in the interval
// of the first sample k whose accumulated weight sum_{j<=k} w_j reaches 1/2, at
//   t_k + delta_k * ln(2 T_k) / (-ln(1 - alpha_k)),  T_k = 1 - sum_{j<k} w_j,  alpha_k = w_k / T_k
// (clamped to the interval). A ray whose weights never reach 1/2 gets its last sample's t.
// Overwrites out[3 r] (depth) only; weights as written by render_volume_fwd for the same rays.
// Sequential sum in sample order: deterministic.
__kernel void render_median_depth(const int n_rays, const int n_samples, const float last_delta,
                                  __global const float* t, __global const float* weights,
                                  __global float* out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int base = r * n_samples;
  float before = 0.0f, depth = t[base + n_samples - 1];
  for (int i = 0; i < n_samples; ++i) {
    const float w = weights[base + i];
    if (before + w >= 0.5f) {
      const int s = base + i;
      const float delta = i + 1 < n_samples ? t[s + 1] - t[s] : last_delta;
      const float T = 1.0f - before, alpha = fmin(w / fmax(T, 1e-30f), 1.0f);
      const float tau = -log1p(-fmin(alpha, 1.0f - 1e-7f));  // sigma_k delta_k > 0
      const float frac = fmin(fmax(log(2.0f * T) / tau, 0.0f), 1.0f);
      depth = t[s] + frac * delta;
      break;
    }
    before += w;
  }
  out[3 * r] = depth;
}

// The spread of a ray's weights (the evaluation's "mix" depth, GS-LiDAR's): per ray
// stats[2 r] = A = sum_i w_i (the opacity) and stats[2 r + 1] = sum_i w_i (t_i - m)^2 / A with
// m = sum_i w_i t_i / A (0 when A < 1e-12). Weights as written by render_volume_fwd.
// Sequential sums in sample order: deterministic.
__kernel void render_depth_spread(const int n_rays, const int n_samples, __global const float* t,
                                  __global const float* weights, __global float* stats) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int base = r * n_samples;
  float a = 0.0f, m = 0.0f;
  for (int i = 0; i < n_samples; ++i) {
    a += weights[base + i];
    m += weights[base + i] * t[base + i];
  }
  float v = 0.0f;
  if (a >= 1e-12f) {
    m /= a;
    for (int i = 0; i < n_samples; ++i) {
      const float e = t[base + i] - m;
      v += weights[base + i] * e * e;
    }
    v /= a;
  }
  stats[2 * r] = a;
  stats[2 * r + 1] = v;
}
