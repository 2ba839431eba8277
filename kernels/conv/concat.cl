// Channel copy between NHWC images with channel strides and offsets: the skip half of the
// U-Net's concatenation [skip, upsampled] (LiDAR4D's torch.cat([x2, x1], dim=1), method.md §2)
// forward, and its split in the backward (with accumulation, since a skip feature also feeds
// the next down stage). Work-item = one (pixel, channel), channels fastest (flat index
// p·C + c); memory-bound.
// dst[p·dst_cs + dst_off + c] (=|+=) src[p·src_cs + src_off + c], c < C, p < n_pix.
__kernel void conv_copy_channels(const int n_pix, const int C, const int src_cs,
                                 const int src_off, const int dst_cs, const int dst_off,
                                 const int accumulate, __global const float* src,
                                 __global float* dst) {
  const int i = get_global_id(0);
  if (i >= n_pix * C) return;
  const int p = i / C, c = i - p * C;
  const float v = src[(size_t)p * src_cs + src_off + c];
  __global float* d = dst + (size_t)p * dst_cs + dst_off + c;
  *d = accumulate ? *d + v : v;
}
