// DirEncoding host launcher (kernels/field/direnc.cl).
#include "field/dir_encoding.hpp"

#include <string>

#include "cl/launch.hpp"
#include "core/error.hpp"

namespace sgnlf::field {
namespace {
void check_bytes(const cl::Buffer& b, size_t floats, const char* what) {
  if (b.bytes() < floats * sizeof(float))
    throw Error(std::string("DirEncoding: buffer '") + what + "' has " +
                std::to_string(b.bytes()) + " bytes, needs " + std::to_string(floats * 4));
}
}  // namespace

DirEncoding::DirEncoding(cl::Runtime& rt, int n_freq, int n_geo, int geo_start, int dens_stride)
    : rt_(rt), n_freq_(n_freq), n_geo_(n_geo), geo_start_(geo_start), dens_stride_(dens_stride) {
  if (n_freq < 1 || n_freq > 20)
    throw ConfigError("DirEncoding: n_freq = " + std::to_string(n_freq) + " outside [1, 20]");
  if (n_geo < 0 || geo_start < 0 || geo_start + n_geo > dens_stride)
    throw ConfigError("DirEncoding: geometric columns [" + std::to_string(geo_start) + ", +" +
                      std::to_string(n_geo) + ") do not fit rows of " +
                      std::to_string(dens_stride));
  const std::string opt = "-DN_FREQ=" + std::to_string(n_freq);
  const std::string f = "field/direnc.cl";
  // Under the gpu profile (ray_work_items > 1) a work-item per (ray, frequency): direnc.cl.
  wide_ = rt_.device_profile().ray_work_items > 1;
  fwd_ = rt_.kernel(f, wide_ ? "field_direnc_fwd_wide" : "field_direnc_fwd", opt);
  bwd_ = rt_.kernel(f, wide_ ? "field_direnc_bwd_wide" : "field_direnc_bwd", opt);
  head_fwd_ = rt_.kernel(f, "field_head_input_fwd", opt);
  head_bwd_geo_ = rt_.kernel(f, "field_head_input_bwd_geo", opt);
  head_bwd_dir_ = rt_.kernel(f, "field_head_input_bwd_dir", opt);
}

void DirEncoding::forward(const cl::Buffer& dir, int n_rays, cl::Buffer& enc) {
  if (n_rays <= 0) return;
  check_bytes(dir, size_t(n_rays) * 3, "dir");
  check_bytes(enc, size_t(n_rays) * enc_dim(), "enc");
  fwd_.set_args(n_rays, dir, enc);
  cl::launch_1d(fwd_, size_t(n_rays) * (wide_ ? size_t(n_freq_) : 1));
}

void DirEncoding::backward(const cl::Buffer& dir, int n_rays, const cl::Buffer& d_enc,
                           cl::Buffer& d_dir) {
  if (n_rays <= 0) return;
  check_bytes(dir, size_t(n_rays) * 3, "dir");
  check_bytes(d_enc, size_t(n_rays) * enc_dim(), "d_enc");
  check_bytes(d_dir, size_t(n_rays) * 3, "d_dir");
  bwd_.set_args(n_rays, dir, d_enc, d_dir);
  if (!wide_) {
    cl::launch_1d(bwd_, size_t(n_rays));
    return;
  }
  // DIRENC_LANES and DIRENC_WG of direnc.cl: the frequencies rounded up to a power of two, and
  // 64 work-items a group.
  size_t lanes = 1;
  while (lanes < size_t(n_freq_)) lanes *= 2;
  const size_t rays_per_group = 64 / lanes;
  bwd_.launch({lanes, cl::round_up(size_t(n_rays), rays_per_group)}, {lanes, rays_per_group});
}

void DirEncoding::head_input_forward(const cl::Buffer& dens, const cl::Buffer& enc, int n_rays,
                                     int samples, cl::Buffer& head_in) {
  if (n_rays <= 0 || samples <= 0) return;
  const size_t n = size_t(n_rays) * size_t(samples);
  check_bytes(dens, n * dens_stride_, "dens");
  check_bytes(enc, size_t(n_rays) * enc_dim(), "enc");
  check_bytes(head_in, n * head_width(), "head_in");
  head_fwd_.set_args(int(n), samples, n_geo_, geo_start_, dens_stride_, dens, enc, head_in);
  cl::launch_1d(head_fwd_, n);
}

void DirEncoding::head_input_backward(const cl::Buffer& d_head_in, int n_rays, int samples,
                                      cl::Buffer& d_dens, cl::Buffer& d_enc) {
  if (n_rays <= 0 || samples <= 0) return;
  const size_t n = size_t(n_rays) * size_t(samples);
  check_bytes(d_head_in, n * head_width(), "d_head_in");
  check_bytes(d_dens, n * dens_stride_, "d_dens");
  check_bytes(d_enc, size_t(n_rays) * enc_dim(), "d_enc");
  head_bwd_geo_.set_args(int(n), n_geo_, geo_start_, dens_stride_, d_head_in, d_dens);
  cl::launch_1d(head_bwd_geo_, n);
  head_bwd_dir_.set_args(n_rays, samples, n_geo_, d_head_in, d_enc);
  const size_t groups = enc_dim() % 8 == 0 ? size_t(enc_dim() / 8) : size_t(enc_dim() / 2);
  head_bwd_dir_.launch({groups, cl::round_up(size_t(n_rays), 8)}, {groups, 8});
}

}  // namespace sgnlf::field
