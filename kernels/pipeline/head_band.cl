// Head band (render.head_weight_threshold, pipeline module, launched by pipeline::HeadBand):
// the LiDAR head runs only on the band of each ray's live samples whose weight exceeds the
// threshold. Host references: tests/pipeline/test_head_band.cpp.

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
