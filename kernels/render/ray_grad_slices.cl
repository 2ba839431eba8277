// The ray gradient reduction over compact sample rows (kernels/render/ray_grad.cl,
// render_raygrad_reduce_rows, has the formulas and the row layout) with a slice of RAY_W
// work-items per ray (device profile ray_work_items > 1; kernels/render/ray_slice.clh): lane l
// sums a contiguous run of the ray's rows, in order, and a fixed tree over the lanes adds the
// runs. Several rays per work-group of the profile's local size, as volume_slices.cl says why.
// Deterministic per device; not ray_grad.cl's bits (the sums associate differently).
#include "render/ray_slice.clh"

__kernel void render_raygrad_reduce_rows_slices(const int n_rays, const int M, const float bound,
                                                const int use_offset, __global const int* offset,
                                                __global const float* t, __global const float* o,
                                                __global const float* d,
                                                __global const float* grad_x,
                                                __global float* grad_o, __global float* grad_d) {
  __local float8 part[RAY_WG];
  const int lane = get_local_id(0) % RAY_W, slot = get_local_id(0) - lane;
  const int r = get_global_id(0) / RAY_W;
  const int valid = r < n_rays;
  const int first = valid ? (use_offset ? offset[r] : r * M) : 0;
  const int count = valid ? (use_offset ? offset[r + 1] - first : M) : 0;
  const float3 orig = valid ? vload3(r, o) : (float3)(0.0f);
  const float3 dir = valid ? vload3(r, d) : (float3)(0.0f);
  int lo, hi;
  ray_slice_range(count, lane, &lo, &hi);
  float3 go = (float3)(0.0f), gd = (float3)(0.0f);
  for (int i = lo; i < hi; ++i) {
    const float ti = t[(size_t)r * M + i];
    const float3 x = orig + ti * dir;
    float3 g = vload3(first + i, grad_x);
    g = select(g, (float3)(0.0f), isgreater(fabs(x), (float3)(bound)));
    go += g;
    gd += ti * g;
  }
  const float8 sum =
      ray_slice_sum8((float8)(go.x, go.y, go.z, gd.x, gd.y, gd.z, 0.0f, 0.0f), lane, part + slot);
  if (lane == 0 && valid) {
    vstore3(sum.s012, r, grad_o);
    vstore3(sum.s345, r, grad_d);
  }
}
