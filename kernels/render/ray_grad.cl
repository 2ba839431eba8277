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
