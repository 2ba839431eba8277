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

// The termination index of one ray's coarse weights wr (S of them): j + 2 for the first j
// after which 1 − Σ_{i≤j} wr[i] < eps, or −1 when there is none with j + 2 < S. Shared by
// pipeline_live_count and pipeline_wave_done, which must agree on it exactly.
inline int pipeline_stop_index(__global const float* wr, const int S, const float eps) {
  float acc = 0.0f;
  for (int j = 0; j + 2 < S; ++j) {
    acc += wr[j];
    if (1.0f - acc < eps) return j + 2;
  }
  return -1;
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
  const int stop = pipeline_stop_index(w_c + (size_t)r * S, S, eps);
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

// buf[k] = value.
__kernel void pipeline_fill(const int n, const float value, __global float* buf) {
  const int k = get_global_id(0);
  if (k >= n) return;
  buf[k] = value;
}

// Coarse waves (render.coarse_waves): the rows of wave [s0, s0 + width) of the rays still
// alive. Row q = a·width + i holds coarse sample s0 + i of ray alive[a]:
// x_w[q] = x_c[alive[a]·S + s0 + i] (3 floats).
__kernel void pipeline_wave_gather(const int n_alive, const int S, const int s0, const int width,
                                   __global const int* alive, __global const float* x_c,
                                   __global float* x_w) {
  const int q = get_global_id(0);
  if (q >= n_alive * width) return;
  const int a = q / width, i = q - a * width;
  const size_t src = ((size_t)alive[a] * S + s0 + i) * 3;
  x_w[3 * (size_t)q + 0] = x_c[src + 0];
  x_w[3 * (size_t)q + 1] = x_c[src + 1];
  x_w[3 * (size_t)q + 2] = x_c[src + 2];
}

// The inverse for the wave's outputs: the encodings (lf floats per row) into the coarse
// layout (enc_c, reused by the merged pass) and the σ logit (column 0 of dens_w, dens_stride
// floats per row) into h0_c.
__kernel void pipeline_wave_scatter(const int n_alive, const int S, const int s0, const int width,
                                    const int lf, const int dens_stride,
                                    __global const int* alive, __global const float* enc_w,
                                    __global const float* dens_w, __global float* enc_c,
                                    __global float* h0_c) {
  const int q = get_global_id(0);
  if (q >= n_alive * width) return;
  const int a = q / width, i = q - a * width;
  const size_t dst = (size_t)alive[a] * S + s0 + i;
  for (int k = 0; k < lf; ++k) enc_c[dst * lf + k] = enc_w[(size_t)q * lf + k];
  h0_c[dst] = dens_w[(size_t)q * dens_stride];
}

// done[r] = 1 when ray r needs no coarse sample at or beyond `end`: its termination index
// (pipeline_stop_index, as pipeline_live_count finds it) lies below `end`. Samples
// not evaluated yet sit at a dead σ (zero weight) and move no sum, so the first j found over
// the evaluated prefix is the one the complete pass finds.
__kernel void pipeline_wave_done(const int n_rays, const int S, const int end, const float eps,
                                 __global const float* w_c, __global int* done) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int stop = pipeline_stop_index(w_c + (size_t)r * S, S, eps);
  done[r] = stop >= 0 && stop < end ? 1 : 0;
}

// Head band (render.head_weight_threshold, LiDAR-NeRF evaluates its heads only where the
// weight exceeds 1e-4): per ray, the contiguous band of its live samples [0, live[r]) from the
// first to the last with w > thr. begin[r] = its first sample, count[r] = its length (0: none).
__kernel void pipeline_head_band(const int n_rays, const int M, const float thr,
                                 __global const int* live_offset, __global const float* w,
                                 __global int* begin, __global int* count) {
  const int r = get_global_id(0);
  if (r >= n_rays) return;
  const int live = live_offset[r + 1] - live_offset[r];
  __global const float* wr = w + (size_t)r * M;
  int first = -1, last = -1;
  for (int s = 0; s < live; ++s)
    if (wr[s] > thr) {
      if (first < 0) first = s;
      last = s;
    }
  begin[r] = first < 0 ? 0 : first;
  count[r] = first < 0 ? 0 : last - first + 1;
}

// Band rows from a layout of `ray_stride`-spaced rays: out[band_offset[r] + i] =
// in[base(r) + begin[r] + i] (`width` floats per row), base(r) = r·M for the full sample layout
// (base_offset null) or base_offset[r] for the live (compacted) layout.
__kernel void pipeline_band_gather(const int n_rays, const int M, const int width,
                                   __global const int* base_offset, __global const int* begin,
                                   __global const int* band_offset, __global const float* in,
                                   __global float* out, const int use_base) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, i = q - r * M;
  const int o = band_offset[r];
  if (i >= band_offset[r + 1] - o) return;
  const size_t src = (size_t)(use_base ? base_offset[r] : r * M) + begin[r] + i;
  for (int k = 0; k < width; ++k) out[(size_t)(o + i) * width + k] = in[src * width + k];
}

// The inverse into the live layout: live rows of the band get the band's row, the other live
// rows zeros (`width` floats per row).
__kernel void pipeline_band_scatter_live(const int n_rays, const int M, const int width,
                                         __global const int* live_offset,
                                         __global const int* begin,
                                         __global const int* band_offset,
                                         __global const float* band, __global float* live) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, s = q - r * M;
  const int lo = live_offset[r];
  if (s >= live_offset[r + 1] - lo) return;
  const int i = s - begin[r], n_band = band_offset[r + 1] - band_offset[r];
  __global float* dst = live + (size_t)(lo + s) * width;
  if (i >= 0 && i < n_band) {
    __global const float* src = band + (size_t)(band_offset[r] + i) * width;
    for (int k = 0; k < width; ++k) dst[k] = src[k];
  } else {
    for (int k = 0; k < width; ++k) dst[k] = 0.0f;
  }
}

// The head outputs into the full sample layout: band samples get the band's 2 logits, every
// other sample `off_logit` in both (sigmoid ≈ 0: LiDAR-NeRF's zero outside its weight mask).
__kernel void pipeline_band_expand_head(const int n_rays, const int M, const float off_logit,
                                        __global const int* begin,
                                        __global const int* band_offset,
                                        __global const float* head_b, __global float* head) {
  const int q = get_global_id(0);
  if (q >= n_rays * M) return;
  const int r = q / M, s = q - r * M;
  const int i = s - begin[r], n_band = band_offset[r + 1] - band_offset[r];
  if (i >= 0 && i < n_band) {
    const size_t row = (size_t)(band_offset[r] + i);
    head[2 * (size_t)q + 0] = head_b[2 * row + 0];
    head[2 * (size_t)q + 1] = head_b[2 * row + 1];
  } else {
    head[2 * (size_t)q + 0] = off_logit;
    head[2 * (size_t)q + 1] = off_logit;
  }
}
