// Ray gradient reduction: positions x_i = o + t_i d give, per ray and in a fixed order,
//   dL/do = sum_i dL/dx_i,   dL/dd = sum_i t_i dL/dx_i
// (t does not depend on the ray). The pose-free methods push these into the poses
// (runtime/render/pose_gradient.hpp). One work-item per ray: deterministic, no atomics.

__kernel void render_raygrad_reduce(const int n_rays, const int n_samples, __global const float* t,
                                    __global const float* grad_x, __global float* grad_o,
                                    __global float* grad_d) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  float3 go = (float3)(0.0f), gd = (float3)(0.0f);
  for (int i = 0; i < n_samples; ++i) {
    const int s = r * n_samples + i;
    const float3 g = vload3(s, grad_x);
    go += g;
    gd += t[s] * g;
  }
  vstore3(go, r, grad_o);
  vstore3(gd, r, grad_d);
}

// The same reduction over a ray's first count[r] samples, stored as rows offset[r] + i of
// grad_x (the compact live rows of early ray termination; without compaction offset[r] = r·M
// and count = M, use_offset = 0). t and the ray (o, d) are in the full R × M layout. The
// sample positions were clamped to [−bound, bound]³ before the field saw them, so a component
// outside the box carries no gradient (the clamp's derivative is 0 there).
__kernel void render_raygrad_reduce_rows(const int n_rays, const int M, const float bound,
                                         const int use_offset, __global const int* offset,
                                         __global const float* t, __global const float* o,
                                         __global const float* d,
                                         __global const float* grad_x, __global float* grad_o,
                                         __global float* grad_d) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int first = use_offset ? offset[r] : r * M;
  const int count = use_offset ? offset[r + 1] - first : M;
  const float3 orig = vload3(r, o), dir = vload3(r, d);
  float3 go = (float3)(0.0f), gd = (float3)(0.0f);
  for (int i = 0; i < count; ++i) {
    const float ti = t[(size_t)r * M + i];
    const float3 x = orig + ti * dir;
    float3 g = vload3(first + i, grad_x);
    g = select(g, (float3)(0.0f), isgreater(fabs(x), (float3)(bound)));
    go += g;
    gd += ti * g;
  }
  vstore3(go, r, grad_o);
  vstore3(gd, r, grad_d);
}
