// Input packing with box dropout (LiDAR4D's ray-drop refinement augmentation, method.md §2):
// out[n, y, x, c] = in[n, y, x, c] · scale[c], or 0 where (y, x) lies in any of the n_boxes
// boxes [y0, y1) × [x0, x1) (boxes[4(box_off + b) + 0..3] = y0, x0, y1, x1), the same boxes
// for every image and channel as in LiDAR4D. n_boxes = 0 is the inference-mode packing (scales
// only). The boxes are drawn on the host from the project's generator (runtime/refine).
// Work-item = one (pixel, channel), channels fastest (flat index p·C + c); memory-bound.
__kernel void conv_box_mask(const int n_img, const int H, const int W, const int C,
                            const int in_cs, const int out_cs, __global const float* scale,
                            const int n_boxes, const int box_off, __global const int* boxes,
                            __global const float* in, __global float* out) {
  const int i = get_global_id(0);
  if (i >= n_img * H * W * C) return;
  const int p = i / C, c = i - p * C;  // p = (n·H + y)·W + x
  const int x = p % W, y = (p / W) % H;
  int keep = 1;
  for (int b = 0; b < n_boxes; ++b) {
    const int4 bx = vload4(box_off + b, boxes);
    if (y >= bx.s0 && x >= bx.s1 && y < bx.s2 && x < bx.s3) keep = 0;
  }
  out[(size_t)p * out_cs + c] = keep ? in[(size_t)p * in_cs + c] * scale[c] : 0.0f;
}
