// Reuse of the coarse pass's hash encodings (pipeline module, launched by
// pipeline::EncodingReuse; method.md §1: the merged sample set is the coarse samples plus the
// importance samples; the coarse ones were already encoded with the same parameters).
// src (from render_sample_importance): k < S for coarse sample k, S + j for importance sample
// j; M = S + I samples per merged ray. Host references: tests/pipeline/test_encoding_reuse.cpp.

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
