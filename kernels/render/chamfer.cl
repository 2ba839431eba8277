// LiDAR4D's Chamfer losses on the device (device profile chamfer: device;
// runtime/render/device_chamfer.hpp, device_scene_flow_loss.hpp): the host's
// render::chamfer_loss, ray_chamfer_loss, scene_flow_loss and ground_flow_penalty
// (render/chamfer_loss.hpp, scene_flow_loss.hpp) without a k-d tree. The sets are small (a batch
// of <= 4096 rays, one frame's few thousand flow points), so nearest neighbours are exact by
// brute force: one work-item per query point, the other set staged through local memory in
// tiles of CHAMFER_WG points. No atomics: every sum has a fixed order (the gradient's in the
// host's point order, the losses' in a fixed tree), so one device gives the same bits each run.
//
// Contraction is off so that a squared distance |p − q|² = dx·dx + dy·dy + dz·dz rounds as
// geometry::squared_distance does on the host (no fma): with IEEE float arithmetic the device
// finds the same distances, and with the same tie rule (below) the same neighbours.
#pragma OPENCL FP_CONTRACT OFF

#ifndef CHAMFER_WG
#define CHAMFER_WG 64
#endif
#ifndef CHAMFER_SUM_WG
#define CHAMFER_SUM_WG 256
#endif

// nn[i], d2[i]: the nearest of t[0..nt) to q[i] (i < nq) and its squared distance. Ties go to
// the lowest index (a later point replaces the best only when strictly nearer), the rule of
// geometry::KdTree::nearest (it compares the input order on exactly equal distances). The two
// can differ only where a device rounds a distance differently from the host (a device without
// IEEE float multiply/add): two candidates at exactly equal host distances may then not be
// equal on the device. nt > 0; every work-item of a group stages its share of each tile.
__kernel void render_chamfer_nearest(const int nq, __global const float* q, const int nt,
                                     __global const float* t, __global int* nn,
                                     __global float* d2) {
  __local float tile[3 * CHAMFER_WG];
  const int i = get_global_id(0), lid = get_local_id(0);
  const bool live = i < nq;
  const float px = live ? q[3 * i] : 0.0f, py = live ? q[3 * i + 1] : 0.0f,
              pz = live ? q[3 * i + 2] : 0.0f;
  float best = INFINITY;
  int best_j = 0;
  for (int base = 0; base < nt; base += CHAMFER_WG) {
    const int j = base + lid;
    if (j < nt) {
      tile[3 * lid] = t[3 * j];
      tile[3 * lid + 1] = t[3 * j + 1];
      tile[3 * lid + 2] = t[3 * j + 2];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    const int m = min(CHAMFER_WG, nt - base);
    for (int k = 0; k < m; ++k) {
      const float dx = px - tile[3 * k], dy = py - tile[3 * k + 1], dz = pz - tile[3 * k + 2];
      const float d = dx * dx + dy * dy + dz * dz;
      if (d < best) {
        best = d;
        best_j = base + k;
      }
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (live) {
    nn[i] = best_j;
    d2[i] = best;
  }
}

// The Chamfer gradient w.r.t. p with the neighbours held fixed (render::chamfer_loss):
//   g_i = c1·(p_i − t_nn1[i]) + Σ_{j : nn2[j] = i, in j order} c2·(p_i − t_j),
// c1 = 2·s1, c2 = 2·s2, in the host's order of float operations. The scatter of the second
// direction is a gather here: work-item i scans nn2 (tiled with t through local memory) for
// its own index, so no two work-items write one place. nt = 0: g_i = 0.
// out[stride·i + offset + k] = (accumulate ? out[...] : 0) + mul·g_i[k].
__kernel void render_chamfer_grad(const int np, __global const float* p, const int nt,
                                  __global const float* t, __global const int* nn1,
                                  __global const int* nn2, const float c1, const float c2,
                                  const float mul, __global float* out, const int stride,
                                  const int offset, const int accumulate) {
  __local float tile[3 * CHAMFER_WG];
  __local int owner[CHAMFER_WG];
  const int i = get_global_id(0), lid = get_local_id(0);
  const bool live = i < np;
  const float px = live ? p[3 * i] : 0.0f, py = live ? p[3 * i + 1] : 0.0f,
              pz = live ? p[3 * i + 2] : 0.0f;
  float gx = 0.0f, gy = 0.0f, gz = 0.0f;
  if (live && nt > 0) {
    const int j = nn1[i];
    gx = c1 * (px - t[3 * j]);
    gy = c1 * (py - t[3 * j + 1]);
    gz = c1 * (pz - t[3 * j + 2]);
  }
  for (int base = 0; base < nt; base += CHAMFER_WG) {
    const int j = base + lid;
    if (j < nt) {
      tile[3 * lid] = t[3 * j];
      tile[3 * lid + 1] = t[3 * j + 1];
      tile[3 * lid + 2] = t[3 * j + 2];
      owner[lid] = nn2[j];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    const int m = min(CHAMFER_WG, nt - base);
    for (int k = 0; k < m; ++k)
      if (owner[k] == i) {
        gx += c2 * (px - tile[3 * k]);
        gy += c2 * (py - tile[3 * k + 1]);
        gz += c2 * (pz - tile[3 * k + 2]);
      }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (!live) return;
  __global float* o = out + (size_t)stride * (size_t)i + offset;
  if (accumulate) {
    o[0] += mul * gx;
    o[1] += mul * gy;
    o[2] += mul * gz;
  } else {
    o[0] = mul * gx;
    o[1] = mul * gy;
    o[2] = mul * gz;
  }
}

// out[slot] = c1·Σ_{i<n1} a[i] + c2·Σ_{i<n2} b[i]: one work-group of CHAMFER_SUM_WG items, each
// summing a strided slice in index order, then a fixed pairwise tree (as render_loss_reduce).
__kernel void render_chamfer_sum(const int n1, __global const float* a, const float c1,
                                 const int n2, __global const float* b, const float c2,
                                 __global float* out, const int slot) {
  __local float pa[CHAMFER_SUM_WG], pb[CHAMFER_SUM_WG];
  const int lid = get_local_id(0);
  float sa = 0.0f, sb = 0.0f;
  for (int i = lid; i < n1; i += CHAMFER_SUM_WG) sa += a[i];
  for (int i = lid; i < n2; i += CHAMFER_SUM_WG) sb += b[i];
  pa[lid] = sa;
  pb[lid] = sb;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int h = CHAMFER_SUM_WG / 2; h > 0; h >>= 1) {
    if (lid < h) {
      pa[lid] += pa[lid + h];
      pb[lid] += pb[lid + h];
    }
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) out[slot] = c1 * pa[0] + c2 * pb[0];
}

// LiDAR4D's ray endpoints (render::ray_chamfer_loss): pred_i = dir_i · (depth_i / scale),
// target_i = dir_i · (range_i / scale), depth = out[3i], range = tgt[3i], both 0 where the
// ray has no return (label tgt[3i + 2] <= 0.5), as LiDAR4D masks them.
__kernel void render_chamfer_ray_points(const int n, __global const float* dir,
                                        __global const float* out, __global const float* tgt,
                                        const float scale, __global float* pred,
                                        __global float* target) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const float mask = tgt[3 * i + 2] > 0.5f ? 1.0f : 0.0f;
  const float sp = (out[3 * i] * mask) / scale, st = (tgt[3 * i] * mask) / scale;
  for (int k = 0; k < 3; ++k) {
    const float d = dir[3 * i + k];
    pred[3 * i + k] = d * sp;
    target[3 * i + k] = d * st;
  }
}

// The ray term's dL/d(depth) added to the output gradient's depth column of rays with a
// return: grad_out[3i] += weight · (g_i · dir_i) / scale.
__kernel void render_chamfer_ray_grad(const int n, __global const float* dir,
                                      __global const float* g, __global const float* tgt,
                                      const float weight, const float scale,
                                      __global float* grad_out) {
  const int i = get_global_id(0);
  if (i >= n || !(tgt[3 * i + 2] > 0.5f)) return;
  const float dot = g[3 * i] * dir[3 * i] + g[3 * i + 1] * dir[3 * i + 1] +
                    g[3 * i + 2] * dir[3 * i + 2];
  grad_out[3 * i] += weight * dot / scale;
}

// The flow supervision's moved points (render::scene_flow_loss): moved_i = x_i + s·flow_i,
// flow_i the forward (side 0) or backward (side 1) displacement of flow[6i..6i+6).
__kernel void render_chamfer_flow_points(const int n, __global const float* x,
                                         __global const float* flow, const int side,
                                         const float s, __global float* moved) {
  const int i = get_global_id(0);
  if (i >= n) return;
  for (int k = 0; k < 3; ++k) moved[3 * i + k] = x[3 * i + k] + s * flow[6 * i + 3 * side + k];
}

// The flow gradient's last step over the (m + g) × 6 flow floats: the moving points' summed
// Chamfer gradients times the supervision's weight, and on the ground points the L1 penalty
// (render::ground_flow_penalty): d_flow = ground_weight · sign(flow), terms[e] = |flow| for the
// sum (render_chamfer_sum, scaled by ground_weight there).
__kernel void render_chamfer_flow_finish(const int m6, const int n6, __global const float* flow,
                                         const float weight, const float ground_weight,
                                         __global float* d_flow, __global float* terms) {
  const int e = get_global_id(0);
  if (e >= n6) return;
  if (e < m6) {
    d_flow[e] = weight * d_flow[e];
    return;
  }
  const float f = flow[e];
  d_flow[e] = f > 0.0f ? ground_weight : f < 0.0f ? -ground_weight : 0.0f;
  terms[e - m6] = fabs(f);
}
