// View-direction frequency encoding and LiDAR-head input assembly (method.md §0 LiDAR head:
// [15 geometric features, frequency encoding of the view direction (12 frequencies, 72 dims)]).
// Encoding layout per ray: enc[k*6 + s*3 + j] = sin(2^k d_j) (s = 0) or cos(2^k d_j) (s = 1).
// Head input per sample i of ray r = i / samples: [dens[i, geo_start .. +n_geo), enc[r]].
#pragma once
#include "cl/runtime.hpp"

namespace sgnlf::field {

class DirEncoding {
 public:
  DirEncoding(cl::Runtime& rt, int n_freq = 12, int n_geo = 15, int geo_start = 1,
              int dens_stride = 16);

  int n_freq() const { return n_freq_; }
  int enc_dim() const { return 6 * n_freq_; }
  int n_geo() const { return n_geo_; }
  int head_width() const { return n_geo_ + enc_dim(); }

  // enc (R × enc_dim) from unit directions dir (R × 3). Enqueued, no wait.
  void forward(const cl::Buffer& dir, int n_rays, cl::Buffer& enc);
  // d_dir (R × 3, overwritten) from d_enc (R × enc_dim). Under the gpu profile (ray_work_items
  // > 1) the frequencies' terms are summed in a fixed tree instead of in order: deterministic,
  // within float rounding of the cpu kernel.
  void backward(const cl::Buffer& dir, int n_rays, const cl::Buffer& d_enc, cl::Buffer& d_dir);

  // head_in (R·S × head_width) from the density-MLP output dens (R·S × dens_stride) and enc.
  void head_input_forward(const cl::Buffer& dens, const cl::Buffer& enc, int n_rays, int samples,
                          cl::Buffer& head_in);
  // Splits d_head_in: writes (overwrites) columns geo_start .. geo_start+n_geo of d_dens, leaves
  // its other columns untouched, and writes d_enc (R × enc_dim) = Σ over each ray's samples in
  // sample order.
  void head_input_backward(const cl::Buffer& d_head_in, int n_rays, int samples,
                           cl::Buffer& d_dens, cl::Buffer& d_enc);

 private:
  cl::Runtime& rt_;
  int n_freq_, n_geo_, geo_start_, dens_stride_;
  bool wide_ = false;  // the profile's ray_work_items > 1 when made: the (ray, frequency) kernels
  cl::Kernel fwd_, bwd_, head_fwd_, head_bwd_geo_, head_bwd_dir_;
};

}  // namespace sgnlf::field
