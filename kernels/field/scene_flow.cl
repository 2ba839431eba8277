// LiDAR4D's scene-flow field, time part (method.md §2; runtime/field/scene_flow.hpp): the 3D
// hash grid gives L levels × F features per point; each level's F features are B consecutive
// chunks of G = F / B, chunk j the features at time node T_j = j / (B − 1), and the flow MLP's
// input is their Lagrange interpolation at the point's time t:
//   out[i, l·G + g] = Σ_j ℓ_j(t_i) · in[i, l·F + j·G + g],
//   ℓ_j(t) = Π_{m≠j} (t − T_m)/(T_j − T_m).
// Time is an input, not differentiated. Defines: LEVELS, FEATURES, BASIS. Host reference:
// tests/field/test_scene_flow.cpp.
#define GROUP (FEATURES / BASIS)

float lagrange_basis(const int j, const float t) {
  float w = 1.0f;
  for (int m = 0; m < BASIS; ++m)
    if (m != j) w *= (t - (float)m / (BASIS - 1)) / ((float)(j - m) / (BASIS - 1));
  return w;
}

// One work-item per point.
__kernel void field_scene_flow_time_fwd(const int n, __global const float* t,
                                        __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  float w[BASIS];
  for (int j = 0; j < BASIS; ++j) w[j] = lagrange_basis(j, t[i]);
  __global const float* row = in + (size_t)i * LEVELS * FEATURES;
  __global float* o = out + (size_t)i * LEVELS * GROUP;
  for (int l = 0; l < LEVELS; ++l)
    for (int g = 0; g < GROUP; ++g) {
      float s = 0.0f;
      for (int j = 0; j < BASIS; ++j) s += w[j] * row[l * FEATURES + j * GROUP + g];
      o[l * GROUP + g] = s;
    }
}

// d_in[i, l·F + j·G + g] = ℓ_j(t_i) · d_out[i, l·G + g] (overwrites).
__kernel void field_scene_flow_time_bwd(const int n, __global const float* t,
                                        __global const float* d_out, __global float* d_in) {
  const int i = get_global_id(0);
  if (i >= n) return;
  float w[BASIS];
  for (int j = 0; j < BASIS; ++j) w[j] = lagrange_basis(j, t[i]);
  __global const float* d = d_out + (size_t)i * LEVELS * GROUP;
  __global float* o = d_in + (size_t)i * LEVELS * FEATURES;
  for (int l = 0; l < LEVELS; ++l)
    for (int j = 0; j < BASIS; ++j)
      for (int g = 0; g < GROUP; ++g) o[l * FEATURES + j * GROUP + g] = w[j] * d[l * GROUP + g];
}

// The same two under the gpu profile (device profile ray_work_items > 1; SceneFlow picks them):
// one work-item per output word instead of per point (a flow batch is a few thousand points),
// each computing the basis weights it needs and the same products and sum order as above.
__kernel void field_scene_flow_time_fwd_wide(const int n, __global const float* t,
                                             __global const float* in, __global float* out) {
  const int q = get_global_id(0);
  if (q >= n * LEVELS * GROUP) return;
  const int i = q / (LEVELS * GROUP), lg = q - i * (LEVELS * GROUP);
  const int l = lg / GROUP, g = lg - l * GROUP;
  float w[BASIS];
  for (int j = 0; j < BASIS; ++j) w[j] = lagrange_basis(j, t[i]);
  __global const float* row = in + (size_t)i * LEVELS * FEATURES;
  float s = 0.0f;
  for (int j = 0; j < BASIS; ++j) s += w[j] * row[l * FEATURES + j * GROUP + g];
  out[q] = s;
}

__kernel void field_scene_flow_time_bwd_wide(const int n, __global const float* t,
                                             __global const float* d_out, __global float* d_in) {
  const int q = get_global_id(0);
  if (q >= n * LEVELS * FEATURES) return;
  const int i = q / (LEVELS * FEATURES), lf = q - i * (LEVELS * FEATURES);
  const int l = lf / FEATURES, jg = lf - l * FEATURES;
  const int j = jg / GROUP, g = jg - j * GROUP;
  d_in[q] = lagrange_basis(j, t[i]) * d_out[(size_t)i * LEVELS * GROUP + l * GROUP + g];
}
