// Weight carving (NeuRAD's L_w; kernels/render/surface.cl, render_weight_carve, has the loss and
// its gradient) with a slice of RAY_W work-items per ray (device profile ray_work_items > 1;
// kernels/render/ray_slice.clh). Lane l takes a contiguous run of the ray's samples: the product
// of its exp(-sigma delta), its sums of m w^2 and g w (g_i = 2 scale m_i w_i); a product scan
// gives T after the run, a suffix sum sum_{i in later runs} g_i w_i, a fixed tree the ray's
// term; then the lane walks its run from the end with
//   dL/dsigma_k = delta_k (g_k T_{k+1} - sum_{i>k} g_i w_i),  T_{k+1} = T_{k+2} + w_{k+1},
// both grown by non-negative terms (surface.cl forms the suffix as total - prefix instead).
// Several rays per work-group of the profile's local size (volume_slices.cl says why).
// Deterministic per device; not surface.cl's bits.
#include "render/ray_slice.clh"

// surface.cl's render_has_return: the label says so and the range lies beyond near.
inline int render_carve_has_return(__global const float* target, int r, float near) {
  return target[3 * r + 2] > 0.5f && target[3 * r] > near;
}

__kernel void render_weight_carve_slices(const int n_rays, const int M, const float last_delta,
                                         const float near, const float half_w, const float scale,
                                         __global const float* t, __global const float* h0,
                                         __global const float* w, __global const float* target,
                                         __global float* g_h0, __global float* terms) {
  __local float part[RAY_WG];
  const int lane = get_local_id(0) % RAY_W, slot = get_local_id(0) - lane;
  const int r = get_global_id(0) / RAY_W;
  const int valid = r < n_rays;
  const int ret = valid && render_carve_has_return(target, r, near);
  const int n = ret ? M : 0, base = ret ? r * M : 0;
  const float rr = ret ? target[3 * r] : 0.0f;
  int lo, hi;
  ray_slice_range(n, lane, &lo, &hi);
  float prod = 1.0f, loss = 0.0f, run = 0.0f;  // run = sum of g_i w_i over the run
  for (int i = lo; i < hi; ++i) {
    const int s = base + i;
    const float delta = i + 1 < M ? t[s + 1] - t[s] : last_delta;
    prod *= exp(-exp(fmin(h0[s], 80.0f)) * delta);
    const float m = fabs(t[s] - rr) > half_w ? 1.0f : 0.0f;
    loss += m * w[s] * w[s];
    run += 2.0f * scale * m * w[s] * w[s];
  }
  float before, suffix;
  float trans = ray_slice_scan_product(prod, lane, part + slot, &before);  // T after the run
  ray_slice_suffix_sum(run, lane, part + slot, &suffix);  // sum over the later runs
  loss = ray_slice_sum(loss, lane, part + slot);
  if (lane == 0 && valid) terms[r] = scale * loss;  // 0 for a ray without a return
  for (int k = hi - 1; k >= lo; --k) {
    const int s = base + k;
    const float delta = k + 1 < M ? t[s + 1] - t[s] : last_delta;
    const float m = fabs(t[s] - rr) > half_w ? 1.0f : 0.0f;
    const float g = 2.0f * scale * m * w[s];
    g_h0[s] += delta * (g * trans - suffix) * exp(clamp(h0[s], -15.0f, 15.0f));
    suffix += g * w[s];
    trans += w[s];
  }
}
