// The pose-free methods' pose gradient on the device (device profile pose_grad: device;
// runtime/render/pose_grad_sums.hpp): the per-ray gradients dL/do, dL/dd (and the direction
// encoding's share of dL/dd) summed over a frame's rays in the world frame,
//   s_o = Σ_r g_o,r,   s_x = Σ_r d_r × (g_d,r + g_dir,r),
// from which the host forms dL/dξ with the SE(3) Jacobians (render::pose_gradient_from_world_sums):
// for rays from the sensor origin, Σ_r v_r × Rᵀ g_d,r = Rᵀ s_x since d_r = R v_r. One
// work-group of POSE_GRAD_WG work-items: work-item l sums rays l, l + WG, ... in index order,
// then a fixed pairwise tree over the work-items. No atomics: the same bits on every run of one
// device (other devices round the sums within float accuracy).
#ifndef POSE_GRAD_WG
#define POSE_GRAD_WG 256
#endif

__kernel void render_pose_grad_sums(const int n_rays, __global const float* d,
                                    __global const float* g_o, __global const float* g_d,
                                    __global const float* g_dir, __global float* out) {
  __local float part[6 * POSE_GRAD_WG];
  const int lid = get_local_id(0);
  float3 so = (float3)(0.0f), sx = (float3)(0.0f);
  for (int r = lid; r < n_rays; r += POSE_GRAD_WG) {
    so += vload3(r, g_o);
    sx += cross(vload3(r, d), vload3(r, g_d) + vload3(r, g_dir));
  }
  part[0 * POSE_GRAD_WG + lid] = so.x;
  part[1 * POSE_GRAD_WG + lid] = so.y;
  part[2 * POSE_GRAD_WG + lid] = so.z;
  part[3 * POSE_GRAD_WG + lid] = sx.x;
  part[4 * POSE_GRAD_WG + lid] = sx.y;
  part[5 * POSE_GRAD_WG + lid] = sx.z;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = POSE_GRAD_WG / 2; h > 0; h >>= 1) {
    if (lid < h)
      for (int k = 0; k < 6; ++k) part[k * POSE_GRAD_WG + lid] += part[k * POSE_GRAD_WG + lid + h];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid < 6) out[lid] = part[lid * POSE_GRAD_WG];
}
