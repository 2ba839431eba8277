// Lidar4DEncoder host code: configuration, the parameter slices and the order of the passes
// (method.md §2): the modules' own launchers plus the small blending steps of
// kernels/field/flow_blend.cl.
#include "field/lidar4d_encoder.hpp"

#include "cl/launch.hpp"
#include "core/error.hpp"
#include "field/frame_time.hpp"

namespace sgnlf::field {

Lidar4DEncoder::Lidar4DEncoder(cl::Runtime& rt, const Lidar4DEncoderConfig& cfg)
    : rt_(rt),
      cfg_(cfg),
      planes_(rt, cfg.planes),
      shash_(rt, cfg.static_hash),
      thash_(rt, cfg.time_hash),
      flow_(rt, cfg.flow) {
  cfg_.validate();
  off_.planes = 0;
  off_.static_hash = off_.planes + planes_.n_params();
  off_.time_hash = off_.static_hash + shash_.n_params();
  off_.flow = off_.time_hash + thash_.n_params();
  off_.end = off_.flow + flow_.n_params();
  const std::string f = "field/flow_blend.cl";
  fill_ = rt_.kernel(f, "field_flow_fill");
  offset_ = rt_.kernel(f, "field_flow_offset");
  blend_fwd_ = rt_.kernel(f, "field_flow_blend_fwd");
  blend_bwd_ = rt_.kernel(f, "field_flow_blend_bwd");
  cols_get_ = rt_.kernel(f, "field_flow_cols_get");
  cols_set_ = rt_.kernel(f, "field_flow_cols_set");
  pack_ = rt_.kernel(f, "field_flow_pack_grad");
  acc_ = rt_.kernel("field/accumulate.cl", "field_accumulate");
}

void Lidar4DEncoder::set_frame(int frame, int first, int frames) {
  const float t = frame_time(frame, first, frames);  // refuses frames outside the sequence
  set_time(t, frames > 1 ? float(1.0 / double(frames - 1)) : 0.0f, frame > first,
           frame < first + frames - 1);
}

void Lidar4DEncoder::set_time(float t, float dt, bool has_prev, bool has_next) {
  if (!(t >= 0.0f && t <= 1.0f) || !(dt >= 0.0f && dt <= 1.0f))
    throw Error("Lidar4DEncoder::set_time: t = " + std::to_string(t) + ", dt = " +
                std::to_string(dt) + " must lie in [0, 1]");
  t_ = t;
  dt_ = dt;
  has_prev_ = has_prev && dt > 0.0f;
  has_next_ = has_next && dt > 0.0f;
}

void Lidar4DEncoder::set_level_weights(const std::vector<float>& w) {
  if (!w.empty())
    throw Error("Lidar4DEncoder: no coarse-to-fine levels, got " + std::to_string(w.size()) +
                " weights");
}

void Lidar4DEncoder::init_params(std::vector<float>& host_params, size_t offset, uint64_t seed) {
  if (offset + off_.end > host_params.size())
    throw Error("Lidar4DEncoder::init_params: slice exceeds buffer of " +
                std::to_string(host_params.size()) + " floats");
  planes_.init_params(host_params, offset + off_.planes, seed);
  shash_.init_params(host_params, offset + off_.static_hash, seed + 1);
  thash_.init_params(host_params, offset + off_.time_hash, seed + 2);
  flow_.init_params(host_params, offset + off_.flow, seed + 3);
}

void Lidar4DEncoder::weights(float& w0, float& w1, float& w2) const {
  const bool on = cfg_.blend;
  w1 = on && has_next_ ? 0.25f : 0.0f;
  w2 = on && has_prev_ ? 0.25f : 0.0f;
  w0 = 1.0f - w1 - w2;  // 0.5 inside, 0.75 at an end, 1 alone
}

void Lidar4DEncoder::ensure(int n) {
  if (capacity_ >= size_t(n)) return;
  const size_t N = size_t(n), d = size_t(dynamic_width()), h = size_t(shash_.n_output());
  for (cl::Buffer* b : {&t0_, &t1_, &t2_}) *b = cl::Buffer(rt_, N * 4);
  for (cl::Buffer* b : {&x1_, &x2_, &dx1_, &dx2_, &dx_tmp_}) *b = cl::Buffer(rt_, N * 12);
  for (cl::Buffer* b : {&flow_out_, &d_flow_}) *b = cl::Buffer(rt_, N * 24);
  for (cl::Buffer* b : {&hs_, &d_hs_}) *b = cl::Buffer(rt_, N * h * 4);
  for (cl::Buffer* b : {&nb1_, &nb2_, &d_own_, &d_nb1_, &d_nb2_}) *b = cl::Buffer(rt_, N * d * 4);
  capacity_ = N;
}

void Lidar4DEncoder::fill(cl::Buffer& b, size_t offset, int n, float v) {
  fill_.set_args(n, v, uint32_t(offset), b);
  cl::launch_1d(fill_, size_t(n));
}

void Lidar4DEncoder::add(const cl::Buffer& src, cl::Buffer& dst, int n) {
  acc_.set_args(n, src, dst);
  cl::launch_1d(acc_, size_t(n));
}

void Lidar4DEncoder::forward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                             cl::Buffer& enc) {
  if (n < 0) throw Error("Lidar4DEncoder: negative point count " + std::to_string(n));
  const int W = width(), P = planes_.n_output(PlaneGroups::Static), H = shash_.n_output();
  const int S = static_width(), D = dynamic_width();
  if (enc.bytes() < size_t(n) * size_t(W) * 4)
    throw Error("Lidar4DEncoder::forward: enc holds " + std::to_string(enc.bytes()) +
                " bytes, needs " + std::to_string(size_t(n) * size_t(W) * 4));
  last_n_ = n;
  if (n == 0) return;
  ensure(n);
  const size_t po = offset + off_.planes, to = offset + off_.time_hash;
  fill(t0_, 0, n, t_);
  planes_.forward(params, po, x, t0_, n, enc, PlaneGroups::Static, W, 0);
  shash_.forward(params, offset + off_.static_hash, x, n, hs_);
  cols_set_.set_args(n, W, P, H, hs_, enc);
  cl::launch_1d(cols_set_, size_t(n));
  planes_.forward(params, po, x, t0_, n, enc, PlaneGroups::Dynamic, W, S);
  thash_.forward_at(params, to, x, t_, n, enc, W, S + P);
  float w0, w1, w2;
  weights(w0, w1, w2);
  if (!uses_flow()) return;
  flow_.forward(params, offset + off_.flow, x, t0_, n, flow_out_);
  auto neighbour = [&](int col, float t, cl::Buffer& xn, cl::Buffer& tn, cl::Buffer& nb) {
    offset_.set_args(n, col, x, flow_out_, xn);
    cl::launch_1d(offset_, size_t(n));
    fill(tn, 0, n, t);
    planes_.forward(params, po, xn, tn, n, nb, PlaneGroups::Dynamic, D, 0);
    thash_.forward_at(params, to, xn, t, n, nb, D, P);
  };
  if (w1 != 0.0f) neighbour(0, next_time(), x1_, t1_, nb1_);
  if (w2 != 0.0f) neighbour(3, prev_time(), x2_, t2_, nb2_);
  blend_fwd_.set_args(n, W, S, D, w0, w1, w2, enc, nb1_, nb2_);
  cl::launch_1d(blend_fwd_, size_t(n));
}

void Lidar4DEncoder::backward(const cl::Buffer& params, size_t offset, const cl::Buffer& x, int n,
                              const cl::Buffer& d_enc, cl::Buffer& grad, size_t grad_offset,
                              cl::Buffer* d_x) {
  if (n != last_n_)
    throw Error("Lidar4DEncoder::backward: " + std::to_string(n) +
                " points, the preceding forward had " + std::to_string(last_n_));
  const int W = width(), P = planes_.n_output(PlaneGroups::Static), H = shash_.n_output();
  const int S = static_width(), D = dynamic_width();
  if (d_enc.bytes() < size_t(n) * size_t(W) * 4)
    throw Error("Lidar4DEncoder::backward: d_enc too small for " + std::to_string(n) + " points");
  const size_t po = offset + off_.planes, to = offset + off_.time_hash;
  const size_t gp = grad_offset + off_.planes, gt = grad_offset + off_.time_hash;
  if (n == 0) return;
  float w0, w1, w2;
  weights(w0, w1, w2);
  cl::Buffer* tmp = d_x ? &dx_tmp_ : nullptr;
  // Static block, read from d_enc in place (the static hash needs its columns dense).
  planes_.backward(params, po, x, t0_, n, d_enc, grad, gp, d_x, PlaneGroups::Static, false, W, 0);
  cols_get_.set_args(n, W, P, H, d_enc, d_hs_);
  cl::launch_1d(cols_get_, size_t(n));
  shash_.backward(params, offset + off_.static_hash, x, n, d_hs_, grad,
                  grad_offset + off_.static_hash, tmp);
  if (d_x) add(dx_tmp_, *d_x, n * 3);
  // Dynamic block: split into the three weighted copies.
  blend_bwd_.set_args(n, W, S, D, w0, w1, w2, d_enc, d_own_, d_nb1_, d_nb2_);
  cl::launch_1d(blend_bwd_, size_t(n));
  planes_.backward(params, po, x, t0_, n, d_own_, grad, gp, tmp, PlaneGroups::Dynamic, false, D,
                   0);
  if (d_x) add(dx_tmp_, *d_x, n * 3);
  thash_.backward_at(params, to, x, t_, n, d_own_, grad, gt, tmp, false, D, P);
  if (d_x) add(dx_tmp_, *d_x, n * 3);
  const size_t gf = grad_offset + off_.flow;
  if (!uses_flow()) {
    fill(grad, gf, int(flow_.n_params()), 0.0f);
    return;
  }
  // Neighbours: parameters accumulate; their position gradient is the flow's (and x's).
  auto neighbour = [&](cl::Buffer& xn, cl::Buffer& tn, float t, cl::Buffer& d_nb,
                       cl::Buffer& dxn) {
    planes_.backward(params, po, xn, tn, n, d_nb, grad, gp, &dxn, PlaneGroups::Dynamic, true, D,
                     0);
    thash_.backward_at(params, to, xn, t, n, d_nb, grad, gt, &dx_tmp_, true, D, P);
    add(dx_tmp_, dxn, n * 3);
    if (d_x) add(dxn, *d_x, n * 3);
  };
  if (w1 != 0.0f) neighbour(x1_, t1_, next_time(), d_nb1_, dx1_);
  if (w2 != 0.0f) neighbour(x2_, t2_, prev_time(), d_nb2_, dx2_);
  pack_.set_args(n, int(w1 != 0.0f), int(w2 != 0.0f), dx1_, dx2_, d_flow_);
  cl::launch_1d(pack_, size_t(n));
  flow_.backward(params, offset + off_.flow, x, t0_, n, flow_out_, d_flow_, grad, gf, tmp);
  if (d_x) add(dx_tmp_, *d_x, n * 3);
}

}  // namespace sgnlf::field
