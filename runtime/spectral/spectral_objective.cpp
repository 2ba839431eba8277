// Batched 5-point evaluation, host loss, device backward (spectral_objective.hpp).
#include "spectral/spectral_objective.hpp"

#include "core/error.hpp"

namespace sgnlf::spectral {

std::vector<float> five_point_inputs(const std::vector<SurfacePoint>& pts, size_t begin, size_t n, double h) {
  std::vector<float> in(size_t(kEvalsPerSample) * n * 3);
  for (size_t i = 0; i < n; ++i) {
    const auto& p = pts[begin + i];
    const Eigen::Vector3d xs[kEvalsPerSample] = {p.x, p.x + h * p.t1, p.x - h * p.t1, p.x + h * p.t2,
                                                 p.x - h * p.t2};
    for (int b = 0; b < kEvalsPerSample; ++b)
      for (int c = 0; c < 3; ++c) in[(b * n + i) * 3 + c] = float(xs[b][c]);
  }
  return in;
}

SpectralObjective::SpectralObjective(cl::Runtime& rt, field::Mlp& psi, const SpectralLossConfig& cfg)
    : rt_(rt), psi_(psi), cfg_(cfg) {
  cfg_.validate();
  require(psi.spec().n_in == 3, "SpectralObjective: Ψ must take 3 inputs");
}

SpectralLossResult SpectralObjective::loss_and_grad(const cl::Buffer& params, size_t offset,
                                                    const std::vector<SurfacePoint>& pts, cl::Buffer& grad,
                                                    size_t grad_offset, double weight) {
  const size_t n = pts.size(), rows = kEvalsPerSample * n;
  const int k = psi_.spec().n_out();
  if (cap_ < rows) {
    in_ = cl::Buffer(rt_, rows * 3 * sizeof(float));
    out_ = cl::Buffer(rt_, rows * k * sizeof(float));
    d_out_ = cl::Buffer(rt_, rows * k * sizeof(float));
    cap_ = rows;
  }
  in_.write_vec(five_point_inputs(pts, 0, n, cfg_.h));
  psi_.forward(params, offset, in_, int(rows), out_, ctx_);
  const auto Y = out_.read_vec<float>(rows * k);
  std::vector<double> w(n);
  double wsum = 0;
  for (size_t i = 0; i < n; ++i) wsum += (w[i] = pts[i].w);
  for (auto& x : w) x /= wsum;
  std::vector<float> dY(rows * k);
  auto res = spectral_loss(Y.data(), n, k, w, cfg_, dY.data());
  if (weight != 1.0)
    for (auto& g : dY) g = float(g * weight);
  d_out_.write_vec(dY);
  psi_.backward(params, offset, ctx_, out_, d_out_, grad, grad_offset);
  return res;
}

SpectralMoments SpectralObjective::moments(const cl::Buffer& params, size_t offset,
                                           const std::vector<SurfacePoint>& pts, size_t chunk) {
  const int k = psi_.spec().n_out();
  SpectralMoments mom(k);
  for (size_t begin = 0; begin < pts.size(); begin += chunk) {
    const size_t n = std::min(chunk, pts.size() - begin), rows = kEvalsPerSample * n;
    if (eval_cap_ < rows) {
      eval_in_ = cl::Buffer(rt_, rows * 3 * sizeof(float));
      eval_out_ = cl::Buffer(rt_, rows * k * sizeof(float));
      eval_cap_ = rows;
    }
    eval_in_.write_vec(five_point_inputs(pts, begin, n, cfg_.h));
    psi_.forward(params, offset, eval_in_, int(rows), eval_out_, eval_ctx_);
    const auto Y = eval_out_.read_vec<float>(rows * k);
    std::vector<double> w(n);
    for (size_t i = 0; i < n; ++i) w[i] = pts[begin + i].w;
    mom.add(Y.data(), n, w, cfg_.h);
  }
  return mom;
}

std::vector<float> SpectralObjective::evaluate(const cl::Buffer& params, size_t offset,
                                               const std::vector<Eigen::Vector3d>& x, size_t chunk) {
  const int k = psi_.spec().n_out();
  std::vector<float> out(x.size() * k);
  for (size_t begin = 0; begin < x.size(); begin += chunk) {
    const size_t n = std::min(chunk, x.size() - begin);
    if (eval_cap_ < n) {
      eval_in_ = cl::Buffer(rt_, n * 3 * sizeof(float));
      eval_out_ = cl::Buffer(rt_, n * k * sizeof(float));
      eval_cap_ = n;
    }
    std::vector<float> in(n * 3);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) in[i * 3 + c] = float(x[begin + i][c]);
    eval_in_.write_vec(in);
    psi_.forward(params, offset, eval_in_, int(n), eval_out_, eval_ctx_);
    eval_out_.read(out.data() + begin * k, n * k * sizeof(float));
  }
  return out;
}

}  // namespace sgnlf::spectral
