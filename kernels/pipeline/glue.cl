// Glue between the field and render modules in a training step (pipeline module):
// strided column gather/scatter (the density MLP writes h0 as column 0 of its N x 16 output,
// the volume renderer reads/writes h0 as a plain N vector) and the clamp of sample positions
// to the normalised scene box [-bound, bound]^3 (LiDAR-NeRF/torch-ngp clamp xyzs to the aabb).
// Host references: tests/pipeline/test_glue.cpp.

// out[i] = in[i * stride + col], i < n.
__kernel void pipeline_column_get(const int n, const int stride, const int col,
                                  __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  out[i] = in[(size_t)i * stride + col];
}

// out[i * stride + col] = in[i], i < n; the other columns of out are left untouched.
__kernel void pipeline_column_set(const int n, const int stride, const int col,
                                  __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n) return;
  out[(size_t)i * stride + col] = in[i];
}

// x[k] = clamp(x[k], -bound, bound) for k < n (n = 3 x points), in place.
__kernel void pipeline_clamp_fwd(const int n, const float bound, __global float* x) {
  const int k = get_global_id(0);
  if (k >= n) return;
  x[k] = clamp(x[k], -bound, bound);
}

// Reuse of the coarse pass's hash encodings (method.md §1: the merged sample set is the coarse
// samples plus the importance samples; the coarse ones were already encoded with the same
// parameters). src (from render_sample_importance): k < S for coarse sample k, S + j for
// importance sample j; M = S + I samples per merged ray.

// x_fine[r * I + j] = x[q] for each merged sample q of ray r whose source is S + j.
__kernel void pipeline_fine_points(const int n_rays, const int S, const int M,
                                   __global const int* src, __global const float* x,
                                   __global float* x_fine) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int s = src[q];
  if (s < S) return;
  const int f = (q / M) * (M - S) + (s - S);
  x_fine[3 * f + 0] = x[3 * q + 0];
  x_fine[3 * f + 1] = x[3 * q + 1];
  x_fine[3 * f + 2] = x[3 * q + 2];
}

// Merged rows in sample order: coarse sources copy their encoding row (width floats) and their
// position from the coarse buffers (so the backward scatters at the point the forward read),
// importance sources copy their row from enc_fine.
__kernel void pipeline_merge_encodings(const int n_rays, const int S, const int M,
                                       const int width, __global const int* src,
                                       __global const float* x_coarse,
                                       __global const float* enc_coarse,
                                       __global const float* enc_fine, __global float* x,
                                       __global float* enc) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int s = src[q], r = q / M;
  __global const float* row;
  if (s < S) {
    const int c = r * S + s;
    x[3 * q + 0] = x_coarse[3 * c + 0];
    x[3 * q + 1] = x_coarse[3 * c + 1];
    x[3 * q + 2] = x_coarse[3 * c + 2];
    row = enc_coarse + (size_t)c * width;
  } else {
    row = enc_fine + (size_t)(r * (M - S) + (s - S)) * width;
  }
  __global float* dst = enc + (size_t)q * width;
  for (int k = 0; k < width; ++k) dst[k] = row[k];
}

// Early ray termination (render.stop_transmittance, instant-ngp / torch-ngp's T threshold):
// merged samples behind the point where the coarse pass's transmittance fell below eps carry
// weight below eps and are not evaluated. Per ray, with coarse weights w_c (S per ray, sorted
// t_c): j = first coarse sample after which 1 − Σ_{i≤j} w_c[i] < eps; the ray keeps its merged
// samples with t ≤ t_c[j + 2] (one more coarse bin of margin), all M when there is no such j
// or j + 2 ≥ S. Merged samples are sorted, so the live ones are a prefix of count[r].
__kernel void pipeline_live_count(const int n_rays, const int S, const int M, const float eps,
                                  __global const float* t_c, __global const float* w_c,
                                  __global const float* t, __global int* count) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  __global const float* wr = w_c + (size_t)r * S;
  float acc = 0.0f;
  int stop = -1;
  for (int j = 0; j + 2 < S; ++j) {
    acc += wr[j];
    if (1.0f - acc < eps) {
      stop = j + 2;
      break;
    }
  }
  int c = M;
  if (stop >= 0) {
    const float t_stop = t_c[(size_t)r * S + stop];
    __global const float* tr = t + (size_t)r * M;
    c = 0;
    while (c < M && tr[c] <= t_stop) ++c;
  }
  count[r] = c;
}

// Compact rows: for ray r and sample s < count[r] (count[r] = offset[r + 1] − offset[r]),
// out[offset[r] + s] = in[r·M + s], `width` floats per row.
__kernel void pipeline_compact_rows(const int n_rays, const int M, const int width,
                                    __global const int* offset, __global const float* in,
                                    __global float* out) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, s = q - r * M;
  const int o = offset[r];
  if (s >= offset[r + 1] - o) return;
  __global const float* src = in + (size_t)q * width;
  __global float* dst = out + (size_t)(o + s) * width;
  for (int k = 0; k < width; ++k) dst[k] = src[k];
}

// The inverse for the field outputs the renderer reads: h0[q] = dens[row·dens_stride] (σ logit,
// column 0) and head[q] = head_c[row] (2 values) for live samples; dead samples get
// h0 = dead_h0 (σ = exp(dead_h0) ≈ 0: zero weight) and head = 0.
__kernel void pipeline_expand_outputs(const int n_rays, const int M, const int dens_stride,
                                      const float dead_h0, __global const int* offset,
                                      __global const float* dens, __global const float* head_c,
                                      __global float* h0, __global float* head) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, s = q - r * M;
  const int o = offset[r];
  if (s < offset[r + 1] - o) {
    const size_t row = (size_t)(o + s);
    h0[q] = dens[row * dens_stride];
    head[2 * q + 0] = head_c[2 * row + 0];
    head[2 * q + 1] = head_c[2 * row + 1];
  } else {
    h0[q] = dead_h0;
    head[2 * q + 0] = 0.0f;
    head[2 * q + 1] = 0.0f;
  }
}

// ray[k] = r for the compact rows k of ray r (offset[r] ≤ k < offset[r + 1]).
__kernel void pipeline_row_ray(const int n_rays, __global const int* offset, __global int* ray) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  for (int k = offset[r]; k < offset[r + 1]; ++k) ray[k] = r;
}

// dst[k] += src[k]: an external gradient (the adversarial consistency term) joins the range
// loss's gradient before the Adam step (LidarNerfModel::update).
__kernel void pipeline_add_inplace(const int n, __global const float* src, __global float* dst) {
  const int k = get_global_id(0);
  if (k >= n) return;
  dst[k] += src[k];
}
