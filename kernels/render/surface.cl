// Training samples placed by the measured return, and the weight-carving loss that concentrates
// the rendered weights there (render/surface_sampler.hpp, render/weight_carving.hpp). Rays are
// given as origins o and unit directions d (n_rays x 3, normalised frame); the targets are
// n_rays x 3 (range in normalised units, intensity, return label 0/1). Samples are ray-major,
// M = F + B + K per ray, sorted. One work-item per ray (per sample for the gpu profile's
// sampler), fixed order: deterministic.
// Host references: tests/render/surface_reference.hpp.
#include "common/philox.clh"

#define RENDER_STREAM_SURFACE 0x52454e33u

// A ray has a return when its label says so and its range lies beyond near.
inline int render_has_return(__global const float* target, int r, float near) {
  return target[3 * r + 2] > 0.5f && target[3 * r] > near;
}

// Jitter of sample i of ray r (M per ray): word i % 4 of Philox block
// (step << 32 | r * ceil(M / 4) + i / 4) of RENDER_STREAM_SURFACE; 0.5 without jitter.
inline float render_surface_xi(int jitter, uint seed_lo, uint seed_hi, uint step, int r, int i,
                               int M) {
  if (!jitter) return 0.5f;
  const uint g = (uint)(r * ((M + 3) / 4) + i / 4);
  const uint4 b = philox_block(seed_lo, seed_hi, RENDER_STREAM_SURFACE, ((ulong)step << 32) | (ulong)g);
  const int w = i % 4;
  const uint bits = w == 0 ? b.x : (w == 1 ? b.y : (w == 2 ? b.z : b.w));
  return philox_unit(bits);
}

// Per ray with a return at range rr: F samples stratified over [near, a], B over [a, b], K - 1
// over [b, c] and the last one over [c, far] (over [b, far] when K = 1), with a = rr - half_w,
// b = rr + half_w, c = rr + half_w + behind (clamped to [near, far]); a ray without a return:
// M stratified over [near, far]. The samples always reach far, as the protocol's do: the
// rendering integral covers the whole ray (cut short at the return, the untrained field's
// opacity is so low that the sigmoid heads saturate making up for it, and never recover).
__kernel void render_sample_surface(const int n_rays, const int F, const int B, const int K,
                                    const float near, const float far, const float half_w,
                                    const float behind, const int jitter, const uint seed_lo,
                                    const uint seed_hi, const uint step, __global const float* o,
                                    __global const float* d, __global const float* target,
                                    __global float* t_out, __global float* x_out) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int M = F + B + K;
  const float3 o3 = vload3(r, o), d3 = vload3(r, d);
  const int ret = render_has_return(target, r, near);
  const float rr = target[3 * r];
  const float a = clamp(rr - half_w, near, far), b = clamp(rr + half_w, near, far),
              c = clamp(rr + half_w + behind, near, far);
  for (int i = 0; i < M; ++i) {
    const float xi = render_surface_xi(jitter, seed_lo, seed_hi, step, r, i, M);
    float t;
    if (!ret) {
      t = near + ((float)i + xi) * ((far - near) / (float)M);
    } else if (i < F) {
      t = near + ((float)i + xi) * ((a - near) / (float)F);
    } else if (i < F + B) {
      t = a + ((float)(i - F) + xi) * ((b - a) / (float)B);
    } else if (i < M - 1) {
      t = b + ((float)(i - F - B) + xi) * ((c - b) / (float)(K - 1));
    } else {  // the last sample: the rest of the ray, so that the samples reach far
      t = (K > 1 ? c : b) + xi * (far - (K > 1 ? c : b));
    }
    const int s = r * M + i;
    t_out[s] = t;
    vstore3(o3 + t * d3, s, x_out);
  }
}

// The same samples under the gpu profile (ray_work_items > 1; SurfaceSampler picks it): one
// work-item per (ray, sample) instead of per ray, each the loop body above for its i. The same
// operations on the same values: the per-ray kernel's samples.
__kernel void render_sample_surface_wide(const int n_rays, const int F, const int B, const int K,
                                         const float near, const float far, const float half_w,
                                         const float behind, const int jitter,
                                         const uint seed_lo, const uint seed_hi, const uint step,
                                         __global const float* o, __global const float* d,
                                         __global const float* target, __global float* t_out,
                                         __global float* x_out) {
  const int M = F + B + K;
  const int s = get_global_id(0);
  if (s >= n_rays * M) return;
  const int r = s / M, i = s - r * M;
  const float3 o3 = vload3(r, o), d3 = vload3(r, d);
  const int ret = render_has_return(target, r, near);
  const float rr = target[3 * r];
  const float a = clamp(rr - half_w, near, far), b = clamp(rr + half_w, near, far),
              c = clamp(rr + half_w + behind, near, far);
  const float xi = render_surface_xi(jitter, seed_lo, seed_hi, step, r, i, M);
  float t;
  if (!ret) {
    t = near + ((float)i + xi) * ((far - near) / (float)M);
  } else if (i < F) {
    t = near + ((float)i + xi) * ((a - near) / (float)F);
  } else if (i < F + B) {
    t = a + ((float)(i - F) + xi) * ((b - a) / (float)B);
  } else if (i < M - 1) {
    t = b + ((float)(i - F - B) + xi) * ((c - b) / (float)(K - 1));
  } else {
    t = (K > 1 ? c : b) + xi * (far - (K > 1 ? c : b));
  }
  t_out[s] = t;
  vstore3(o3 + t * d3, s, x_out);
}

// Weight carving (NeuRAD's L_w): per ray with a return, scale · sum_i m_i w_i^2 where m_i = 1
// for samples with |t_i - range| > half_w; rays without a return carry none. Writes the
// per-ray loss to terms[r] and ADDS dL/dh0 to g_h0 (after the renderer's backward). With
// sigma = exp(min(h0, 80)) and w_i = T_i (1 - e_i), e_i = exp(-sigma_i delta_i):
//   dL/dsigma_k = delta_k (g_k T_{k+1} - sum_{i>k} g_i w_i),  g_i = 2 scale m_i w_i,
// and dsigma/dh0 = exp(clamp(h0, -15, 15)) (the renderer's truncated exponential).
__kernel void render_weight_carve(const int n_rays, const int M, const float last_delta,
                                  const float near, const float half_w, const float scale,
                                  __global const float* t, __global const float* h0,
                                  __global const float* w, __global const float* target,
                                  __global float* g_h0, __global float* terms) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  if (!render_has_return(target, r, near)) {
    terms[r] = 0.0f;
    return;
  }
  const float rr = target[3 * r];
  const int base = r * M;
  float loss = 0.0f, total = 0.0f;  // total = sum_i g_i w_i
  for (int i = 0; i < M; ++i) {
    const float wi = w[base + i];
    const float m = fabs(t[base + i] - rr) > half_w ? 1.0f : 0.0f;
    loss += m * wi * wi;
    total += 2.0f * scale * m * wi * wi;
  }
  terms[r] = scale * loss;
  float trans = 1.0f, prefix = 0.0f;
  for (int k = 0; k < M; ++k) {
    const int s = base + k;
    const float delta = k + 1 < M ? t[s + 1] - t[s] : last_delta;
    const float e = exp(-exp(fmin(h0[s], 80.0f)) * delta);
    trans *= e;  // T_{k+1}
    const float m = fabs(t[s] - rr) > half_w ? 1.0f : 0.0f;
    const float g = 2.0f * scale * m * w[s];
    prefix += g * w[s];
    const float dsigma = delta * (g * trans - (total - prefix));
    g_h0[s] += dsigma * exp(clamp(h0[s], -15.0f, 15.0f));
  }
}
