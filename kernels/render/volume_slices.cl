// Volume rendering along LiDAR rays, forward and backward, with a slice of RAY_W work-items per
// ray (device profile ray_work_items > 1: the gpu profile's 32; kernels/render/ray_slice.clh):
// the same quadrature as kernels/render/volume.cl (its header has the formulas), whose one
// work-item per ray leaves a GPU idle at 4096 rays. Lane l of a ray's slice takes a contiguous
// run of its samples:
//   forward: the product of the run's exp(-sigma delta) -> an exclusive product scan across the
//            lanes gives the transmittance before the run (ray_slice.clh says why a product and
//            not a sum of sigma delta) -> the run's weights and partial depth / probability /
//            intensity sums -> a fixed tree over the lanes.
//   backward: the run's transmittance after it (the inclusive product) and the reverse sum of
//            w (g . c) over the later lanes -> the run walked from its end, T_{i+1} and the
//            suffix sum grown by non-negative terms as in volume.cl.
// Several rays share a work-group of the profile's local size (RAY_WG = local_size rounded down
// to a multiple of RAY_W) rather than one ray per work-group: the work-group keeps the shape the
// profile tunes for the device whatever RAY_W is, and a 32-lane slice is one warp of a wider
// group. Deterministic per device; not volume.cl's bits (the sums associate differently).
// Host references: tests/render/render_reference.hpp.
#include "render/ray_slice.clh"

inline float render_slice_sigmoid(float v) { return 1.0f / (1.0f + exp(-v)); }

// exp(-sigma_i delta_i) of sample i (global index s), as volume.cl computes it.
inline float render_slice_decay(__global const float* t, __global const float* h0, int s, int i,
                                int n_samples, float last_delta) {
  const float delta = i + 1 < n_samples ? t[s + 1] - t[s] : last_delta;
  return exp(-exp(fmin(h0[s], 80.0f)) * delta);
}

// The transmittance before lane `lane`'s run [lo, hi) of ray samples starting at `base`.
inline float render_slice_trans(__global const float* t, __global const float* h0, int base,
                                int lo, int hi, int n_samples, float last_delta, int lane,
                                __local float* s) {
  float prod = 1.0f;
  for (int i = lo; i < hi; ++i)
    prod *= render_slice_decay(t, h0, base + i, i, n_samples, last_delta);
  float before;
  ray_slice_scan_product(prod, lane, s, &before);
  return before;
}

__kernel void render_volume_fwd_slices(const int n_rays, const int n_samples,
                                       const float last_delta, __global const float* t,
                                       __global const float* h0, __global const float* head,
                                       __global float* out, __global float* weights) {
  __local float part[RAY_WG];
  __local float4 sums[RAY_WG];
  const int lane = get_local_id(0) % RAY_W, slot = get_local_id(0) - lane;
  const int r = get_global_id(0) / RAY_W;
  const int n = r < n_rays ? n_samples : 0, base = r < n_rays ? r * n_samples : 0;
  int lo, hi;
  ray_slice_range(n, lane, &lo, &hi);
  float trans = render_slice_trans(t, h0, base, lo, hi, n_samples, last_delta, lane, part + slot);
  float4 acc = (float4)(0.0f);  // depth, probability, intensity
  for (int i = lo; i < hi; ++i) {
    const int s = base + i;
    const float e = render_slice_decay(t, h0, s, i, n_samples, last_delta);
    const float w = trans * (1.0f - e);
    acc += (float4)(w * t[s], w * render_slice_sigmoid(head[2 * s]),
                    w * render_slice_sigmoid(head[2 * s + 1]), 0.0f);
    weights[s] = w;
    trans *= e;
  }
  acc = ray_slice_sum4(acc, lane, sums + slot);
  if (lane == 0 && r < n_rays) {
    out[3 * r + 0] = acc.x;
    out[3 * r + 1] = acc.y;
    out[3 * r + 2] = acc.z;
  }
}

// Weights only (the coarse pass of importance sampling): the forward's code without the head,
// so the weights are bit-identical to the forward's.
__kernel void render_volume_weights_slices(const int n_rays, const int n_samples,
                                           const float last_delta, __global const float* t,
                                           __global const float* h0, __global float* weights) {
  __local float part[RAY_WG];
  const int lane = get_local_id(0) % RAY_W, slot = get_local_id(0) - lane;
  const int r = get_global_id(0) / RAY_W;
  const int n = r < n_rays ? n_samples : 0, base = r < n_rays ? r * n_samples : 0;
  int lo, hi;
  ray_slice_range(n, lane, &lo, &hi);
  float trans = render_slice_trans(t, h0, base, lo, hi, n_samples, last_delta, lane, part + slot);
  for (int i = lo; i < hi; ++i) {
    const int s = base + i;
    const float e = render_slice_decay(t, h0, s, i, n_samples, last_delta);
    weights[s] = trans * (1.0f - e);
    trans *= e;
  }
}

// Backward (volume.cl's formulas): dL/dtau_i = T_{i+1} c_i - sum_{k>i} w_k c_k with c = g . c.
// A lane gets T after its run from the product scan and sum_{k in later runs} w_k c_k from the
// suffix sum, then walks its run from the end: T_{i+1} = T_{i+2} + w_{i+1} and the suffix sum
// grow by non-negative weights as in volume.cl (no cancellation on opaque rays).
__kernel void render_volume_bwd_slices(const int n_rays, const int n_samples,
                                       const float last_delta, __global const float* t,
                                       __global const float* h0, __global const float* head,
                                       __global const float* weights,
                                       __global const float* grad_out, __global float* grad_h0,
                                       __global float* grad_head) {
  __local float part[RAY_WG];
  const int lane = get_local_id(0) % RAY_W, slot = get_local_id(0) - lane;
  const int r = get_global_id(0) / RAY_W;
  const int valid = r < n_rays;
  const int n = valid ? n_samples : 0, base = valid ? r * n_samples : 0;
  const float g_d = valid ? grad_out[3 * r] : 0.0f, g_p = valid ? grad_out[3 * r + 1] : 0.0f,
              g_i = valid ? grad_out[3 * r + 2] : 0.0f;
  int lo, hi;
  ray_slice_range(n, lane, &lo, &hi);
  float prod = 1.0f, run = 0.0f;  // the run's product of exp(-tau) and sum of w (g . c)
  for (int i = lo; i < hi; ++i) {
    const int s = base + i;
    prod *= render_slice_decay(t, h0, s, i, n_samples, last_delta);
    const float gc = g_d * t[s] + g_p * render_slice_sigmoid(head[2 * s]) +
                     g_i * render_slice_sigmoid(head[2 * s + 1]);
    run += weights[s] * gc;
  }
  float before, suffix;
  float trans = ray_slice_scan_product(prod, lane, part + slot, &before);  // T after the run
  ray_slice_suffix_sum(run, lane, part + slot, &suffix);  // sum over the later runs
  for (int i = hi - 1; i >= lo; --i) {
    const int s = base + i;
    const float w = weights[s];
    const float sp = render_slice_sigmoid(head[2 * s]), si = render_slice_sigmoid(head[2 * s + 1]);
    const float gc = g_d * t[s] + g_p * sp + g_i * si;
    const float delta = i + 1 < n_samples ? t[s + 1] - t[s] : last_delta;
    grad_h0[s] = (trans * gc - suffix) * delta * exp(clamp(h0[s], -15.0f, 15.0f));
    grad_head[2 * s] = g_p * w * sp * (1.0f - sp);
    grad_head[2 * s + 1] = g_i * w * si * (1.0f - si);
    suffix += w * gc;
    trans += w;
  }
}
