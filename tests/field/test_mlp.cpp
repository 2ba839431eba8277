// MLP: device vs host reference (forward, dL/dparams, dL/dinput) for the density, LiDAR-head
// and Ψ shapes and odd widths with every activation; finite differences of the device forward.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "core/rng.hpp"
#include "field/mlp.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using field::Activation;

namespace {
using test::uniform;
using test::norm_err;
double dot(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += double(a[i]) * b[i];
  return s;
}
field::MlpSpec odd_spec() {  // widths not multiples of 16, every activation
  field::MlpSpec s;
  s.n_in = 5;
  s.layers = {{20, Activation::Softplus}, {33, Activation::Sine}, {7, Activation::Tanh},
              {3, Activation::Relu}, {2, Activation::Tanh}};
  return s;
}
// Central differences (step h) of loss(v') where v' is v with entry k moved by ±h, for the
// entries k in `which`; appended to fd, the analytic gradients an_all[k] to an.
template <typename Loss>
void central_diffs(const std::vector<float>& v, const std::vector<float>& an_all,
                   const std::vector<size_t>& which, float h, Loss loss, std::vector<float>& fd,
                   std::vector<float>& an) {
  for (size_t k : which) {
    auto vp = v, vm = v;
    vp[k] += h;
    vm[k] -= h;
    fd.push_back(float((loss(vp) - loss(vm)) / (2.0 * h)));
    an.push_back(an_all[k]);
  }
}
// Indices 0, stride, 2·stride, … below n, skipping those where grad is exactly 0 (padding).
std::vector<size_t> every(size_t n, size_t stride, const std::vector<float>* grad = nullptr) {
  std::vector<size_t> k;
  for (size_t i = 0; i < n; i += stride)
    if (!grad || (*grad)[i] != 0.0f) k.push_back(i);
  return k;
}
struct Case {
  const char* name;
  field::MlpSpec spec;
};
std::vector<Case> cases() {
  return {{"density 32-64-16", field::make_mlp_spec(32, 64, 1, 16, Activation::Relu)},
          {"head 87-64x3-2", field::make_mlp_spec(87, 64, 3, 2, Activation::Relu)},
          {"psi 3-64-64-16 tanh", field::make_mlp_spec(3, 64, 2, 16, Activation::Tanh)},
          {"psi sine", field::make_mlp_spec(3, 64, 2, 16, Activation::Sine)},
          {"odd widths", odd_spec()}};
}
}  // namespace

TEST_CASE("MLP forward and backward match the host reference", "[field][mlp]") {
  auto& rt = test::runtime();
  for (const auto& c : cases()) {
    SECTION(c.name) {
      field::Mlp mlp(rt, c.spec);
      const int n = 1000 + 3;  // not a multiple of the tile
      const int ni = c.spec.n_in, no = c.spec.n_out();
      const size_t off = 48;
      std::vector<float> params(off + mlp.n_params(), 0.0f);
      mlp.init_params(params, off, 5);
      // Non-zero biases so the bias path is exercised.
      for (size_t l = 0; l < c.spec.layers.size(); ++l) {
        const int in_l = l == 0 ? ni : c.spec.layers[l - 1].width;
        const int op = field::Mlp::pad16(c.spec.layers[l].width);
        for (int o = 0; o < c.spec.layers[l].width; ++o)
          params[off + mlp.layer_offset(int(l)) + size_t(in_l) * op + o] = 0.05f * (o % 5 - 2);
      }
      const std::vector<float> slice(params.begin() + off, params.end());
      const auto in = uniform(size_t(n) * ni, -1.0f, 1.0f, 6);
      const auto d_out = uniform(size_t(n) * no, -1.0f, 1.0f, 7);
      auto b_p = cl::Buffer::from(rt, params), b_in = cl::Buffer::from(rt, in);
      auto b_dout = cl::Buffer::from(rt, d_out);
      cl::Buffer b_out(rt, size_t(n) * no * 4), b_din(rt, size_t(n) * ni * 4);
      auto b_grad = cl::Buffer::from(rt, std::vector<float>(params.size(), 9.0f));
      field::MlpContext ctx;
      mlp.forward(b_p, off, b_in, n, b_out, ctx);
      mlp.backward(b_p, off, ctx, b_out, b_dout, b_grad, off, &b_din);
      const auto out = b_out.read_vec<float>(size_t(n) * no);
      const auto grad = b_grad.read_vec<float>(params.size());
      const auto din = b_din.read_vec<float>(size_t(n) * ni);

      std::vector<float> din_ref;
      const auto out_ref = test::ref::mlp_fwd(c.spec, slice, in, n);
      const auto g_ref = test::ref::mlp_bwd(c.spec, slice, in, n, d_out, din_ref);
      const std::vector<float> g_dev(grad.begin() + off, grad.end());
      // Float32 GEMMs against a double reference: errors relative to the largest magnitude.
      CHECK(norm_err(out, out_ref) < 1e-5);
      CHECK(norm_err(g_dev, g_ref) < 1e-5);
      CHECK(norm_err(din, din_ref) < 1e-5);
      CHECK(test::max_sym_rel_err(g_dev, g_ref, 1.0) < 1e-4);
      CHECK(grad[off - 1] == 9.0f);  // outside the slice: untouched
      // Padding columns stay zero in the gradient.
      const int op_last = field::Mlp::pad16(no);
      const size_t last = mlp.layer_offset(int(c.spec.layers.size()) - 1);
      for (int o = no; o < op_last; ++o) CHECK(g_dev[last + o] == 0.0f);
    }
  }
}

TEST_CASE("MLP gradients agree with finite differences of the device forward",
          "[field][mlp][fd]") {
  auto& rt = test::runtime();
  // Smooth activations (FD through ReLU kinks is ill-posed); ReLU is covered by the reference.
  field::MlpSpec spec;
  spec.n_in = 6;
  spec.layers = {{24, Activation::Tanh}, {17, Activation::Softplus}, {9, Activation::Sine},
                 {4, Activation::None}};
  field::Mlp mlp(rt, spec);
  const int n = 40, ni = spec.n_in, no = spec.n_out();
  std::vector<float> params(mlp.n_params(), 0.0f);
  mlp.init_params(params, 0, 3);
  const auto in = uniform(size_t(n) * ni, -1.0f, 1.0f, 4);
  const auto r = uniform(size_t(n) * no, -1.0f, 1.0f, 5);  // L = Σ r · out
  auto b_p = cl::Buffer::from(rt, params), b_in = cl::Buffer::from(rt, in);
  auto b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_out(rt, size_t(n) * no * 4), b_din(rt, size_t(n) * ni * 4),
      b_grad(rt, params.size() * 4);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_in, n, b_out, ctx);
  mlp.backward(b_p, 0, ctx, b_out, b_r, b_grad, 0, &b_din);
  const auto grad = b_grad.read_vec<float>(params.size());
  const auto din = b_din.read_vec<float>(size_t(n) * ni);
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& x) {
    b_p.write_vec(p);
    b_in.write_vec(x);
    field::MlpContext c2;
    mlp.forward(b_p, 0, b_in, n, b_out, c2);
    return dot(b_out.read_vec<float>(size_t(n) * no), r);
  };
  const float h = 1e-2f;
  std::vector<float> fd, an;
  central_diffs(params, grad, every(params.size(), 7, &grad), h,
                [&](const std::vector<float>& p) { return loss(p, in); }, fd, an);
  REQUIRE(fd.size() > 50);
  // Central differences: truncation O(h²·f''') ~1e-4, float rounding of L ~1e-6/h.
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
  fd.clear();
  an.clear();
  central_diffs(in, din, every(in.size(), 3), h,
                [&](const std::vector<float>& x) { return loss(params, x); }, fd, an);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
}

namespace {
// The LiDAR head's shape: 15 geometric features read from columns 1..15 of the density output
// (stride 16), the 72-dim direction encoding shared by the samples of a ray (a group). Runs the
// grouped MLP (groups of sizes[g] consecutive points; through a group index when `indexed`,
// else all sizes must be equal) against the plain 87-input MLP on the concatenation and checks
// outputs, parameter gradients, d_in and d_group_in. Returns d_group_in.
std::vector<float> check_grouped_head(const std::vector<int>& sizes, bool indexed, uint64_t seed) {
  auto& rt = test::runtime();
  field::MlpSpec gs = field::make_mlp_spec(15, 64, 3, 2, Activation::Relu);
  gs.n_in_group = 72;
  gs.in_stride = 16;
  gs.in_offset = 1;
  const field::MlpSpec ps = field::make_mlp_spec(87, 64, 3, 2, Activation::Relu);
  field::Mlp grouped(rt, gs), plain(rt, ps);
  REQUIRE(grouped.n_params() == plain.n_params());
  const int G = int(sizes.size()), no = 2;
  std::vector<int32_t> offsets{0}, point_group;
  for (int g = 0; g < G; ++g) {
    offsets.push_back(offsets.back() + sizes[size_t(g)]);
    for (int k = 0; k < sizes[size_t(g)]; ++k) point_group.push_back(g);
  }
  const int n = offsets.back();
  std::vector<float> params(plain.n_params());
  plain.init_params(params, 0, seed);
  std::vector<float> params_g(grouped.n_params());
  grouped.init_params(params_g, 0, seed);
  CHECK(params_g == params);  // same layout and initialisation as the plain MLP
  for (int o = 0; o < 64; ++o) params[size_t(87) * 64 + o] = 0.03f * (o % 7 - 3);  // bias
  const auto wide = uniform(size_t(n) * 16, -1.0f, 1.0f, seed + 1);
  const auto y = uniform(size_t(G) * 72, -1.0f, 1.0f, seed + 2);
  std::vector<float> cat(size_t(n) * 87);
  for (int p = 0; p < n; ++p) {
    for (int c = 0; c < 15; ++c) cat[size_t(p) * 87 + c] = wide[size_t(p) * 16 + 1 + c];
    for (int c = 0; c < 72; ++c)
      cat[size_t(p) * 87 + 15 + c] = y[size_t(point_group[size_t(p)]) * 72 + c];
  }
  const auto d_out = uniform(size_t(n) * no, -1.0f, 1.0f, seed + 3);
  auto b_p = cl::Buffer::from(rt, params), b_dout = cl::Buffer::from(rt, d_out);
  auto b_wide = cl::Buffer::from(rt, wide), b_y = cl::Buffer::from(rt, y);
  auto b_cat = cl::Buffer::from(rt, cat);
  auto b_pg = cl::Buffer::from(rt, point_group), b_off = cl::Buffer::from(rt, offsets);
  const field::GroupIndex index{&b_pg, &b_off, G};
  cl::Buffer b_out_g(rt, size_t(n) * no * 4), b_out_p(rt, size_t(n) * no * 4);
  cl::Buffer b_grad_g(rt, params.size() * 4), b_grad_p(rt, params.size() * 4);
  auto b_din_g = cl::Buffer::from(rt, std::vector<float>(size_t(n) * 16, 7.0f));
  cl::Buffer b_din_p(rt, size_t(n) * 87 * 4);
  auto b_dy = cl::Buffer::from(rt, std::vector<float>(size_t(G) * 72, 5.0f));
  field::MlpContext cg, cp;
  grouped.forward(b_p, 0, b_wide, n, b_out_g, cg, &b_y, indexed ? 0 : sizes[0],
                  indexed ? &index : nullptr);
  grouped.backward(b_p, 0, cg, b_out_g, b_dout, b_grad_g, 0, &b_din_g, &b_dy);
  plain.forward(b_p, 0, b_cat, n, b_out_p, cp);
  plain.backward(b_p, 0, cp, b_out_p, b_dout, b_grad_p, 0, &b_din_p);
  CHECK(norm_err(b_out_g.read_vec<float>(size_t(n) * no), b_out_p.read_vec<float>(size_t(n) * no)) < 1e-5);
  CHECK(norm_err(b_grad_g.read_vec<float>(params.size()), b_grad_p.read_vec<float>(params.size())) < 1e-5);
  const auto din_p = b_din_p.read_vec<float>(size_t(n) * 87);
  const auto din_g = b_din_g.read_vec<float>(size_t(n) * 16);
  std::vector<float> dx_g, dx_p, dy_ref(size_t(G) * 72, 0.0f);
  size_t untouched = 0;
  for (int p = 0; p < n; ++p) {
    untouched += din_g[size_t(p) * 16] == 7.0f;
    for (int c = 0; c < 15; ++c) {
      dx_g.push_back(din_g[size_t(p) * 16 + 1 + c]);
      dx_p.push_back(din_p[size_t(p) * 87 + c]);
    }
    for (int c = 0; c < 72; ++c)
      dy_ref[size_t(point_group[size_t(p)]) * 72 + c] += din_p[size_t(p) * 87 + 15 + c];
  }
  CHECK(untouched == size_t(n));  // column 0 is not the MLP's input: left alone
  CHECK(norm_err(dx_g, dx_p) < 1e-5);
  const auto dy = b_dy.read_vec<float>(dy_ref.size());
  CHECK(norm_err(dy, dy_ref) < 1e-5);
  // Misuse is refused: a group size that does not divide n, a group index without offsets
  // or on an MLP without grouped inputs.
  field::MlpContext bad;
  CHECK_THROWS(grouped.forward(b_p, 0, b_wide, n, b_out_g, bad, &b_y, n - 1));
  const field::GroupIndex no_offsets{&b_pg, nullptr, G};
  CHECK_THROWS(grouped.forward(b_p, 0, b_wide, n, b_out_g, bad, &b_y, 0, &no_offsets));
  CHECK_THROWS(plain.forward(b_p, 0, b_cat, n, b_out_p, bad, nullptr, 0, &index));
  return dy;
}
}  // namespace

TEST_CASE("grouped inputs compute the plain MLP on [x, y] with the same gradients",
          "[field][mlp]") {
  check_grouped_head(std::vector<int>(37, 13), false, 11);
}

TEST_CASE("grouped-input MLP gradients agree with finite differences", "[field][mlp][fd]") {
  auto& rt = test::runtime();
  field::MlpSpec spec;
  spec.n_in = 4;
  spec.n_in_group = 5;
  spec.in_stride = 6;
  spec.in_offset = 2;
  spec.layers = {{12, Activation::Tanh}, {7, Activation::Softplus}, {3, Activation::None}};
  field::Mlp mlp(rt, spec);
  const int G = 6, group = 4, n = G * group, no = 3;
  std::vector<float> params(mlp.n_params(), 0.0f);
  mlp.init_params(params, 0, 21);
  const auto x = uniform(size_t(n) * 6, -1.0f, 1.0f, 22);
  const auto y = uniform(size_t(G) * 5, -1.0f, 1.0f, 23);
  const auto r = uniform(size_t(n) * no, -1.0f, 1.0f, 24);  // L = Σ r · out
  auto b_p = cl::Buffer::from(rt, params), b_x = cl::Buffer::from(rt, x);
  auto b_y = cl::Buffer::from(rt, y), b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_out(rt, size_t(n) * no * 4), b_dx(rt, x.size() * 4), b_dy(rt, y.size() * 4),
      b_grad(rt, params.size() * 4);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, group);
  mlp.backward(b_p, 0, ctx, b_out, b_r, b_grad, 0, &b_dx, &b_dy);
  const auto grad = b_grad.read_vec<float>(params.size());
  const auto dx = b_dx.read_vec<float>(x.size()), dy = b_dy.read_vec<float>(y.size());
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& xv,
                  const std::vector<float>& yv) {
    b_p.write_vec(p);
    b_x.write_vec(xv);
    b_y.write_vec(yv);
    field::MlpContext c2;
    mlp.forward(b_p, 0, b_x, n, b_out, c2, &b_y, group);
    return dot(b_out.read_vec<float>(size_t(n) * no), r);
  };
  const float h = 1e-2f;
  std::vector<float> fd, an;
  central_diffs(params, grad, every(params.size(), 3, &grad), h,
                [&](const std::vector<float>& p) { return loss(p, x, y); }, fd, an);
  REQUIRE(fd.size() > 40);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
  fd.clear();
  an.clear();
  std::vector<size_t> x_cols;  // the per-point columns 2..5 of each row
  for (int p = 0; p < n; ++p)
    for (int c = 0; c < 4; ++c) x_cols.push_back(size_t(p) * 6 + 2 + size_t(c));
  central_diffs(x, dx, x_cols, h, [&](const std::vector<float>& xv) { return loss(params, xv, y); },
                fd, an);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
  fd.clear();
  an.clear();
  central_diffs(y, dy, every(y.size(), 1), h,
                [&](const std::vector<float>& yv) { return loss(params, x, yv); }, fd, an);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
}

TEST_CASE("groups of varying size (a group index) compute the plain MLP on [x, y]",
          "[field][mlp]") {
  auto& rt = test::runtime();
  // The LiDAR head after early ray termination: each ray keeps a varying number of samples
  // (possibly none); the direction encoding is shared by a ray's live samples.
  const std::vector<int> sizes = {5, 0, 17, 1, 9, 0, 33, 2, 8, 21, 3};
  const auto dy = check_grouped_head(sizes, true, 31);
  for (int c = 0; c < 72; ++c) {  // empty groups get a zero gradient row, not stale memory
    CHECK(dy[size_t(1) * 72 + c] == 0.0f);
    CHECK(dy[size_t(5) * 72 + c] == 0.0f);
  }
  const int G = int(sizes.size());
  std::vector<int32_t> offsets{0}, point_group;
  for (int g = 0; g < G; ++g) {
    offsets.push_back(offsets.back() + sizes[size_t(g)]);
    for (int k = 0; k < sizes[size_t(g)]; ++k) point_group.push_back(g);
  }
  const int n = offsets.back();
  auto b_pg = cl::Buffer::from(rt, point_group), b_off = cl::Buffer::from(rt, offsets);
  const field::GroupIndex index{&b_pg, &b_off, G};
  // Finite differences of the device forward (a smooth MLP: ReLU kinks would break them) with
  // respect to the parameters and the shared inputs y, with the same varying groups.
  field::MlpSpec ss;
  ss.n_in = 4;
  ss.n_in_group = 5;
  ss.in_stride = 6;
  ss.in_offset = 2;
  ss.layers = {{12, Activation::Tanh}, {7, Activation::Softplus}, {3, Activation::None}};
  field::Mlp smooth(rt, ss);
  std::vector<float> sp(smooth.n_params(), 0.0f);
  smooth.init_params(sp, 0, 36);
  const auto sx = uniform(size_t(n) * 6, -1.0f, 1.0f, 37);
  const auto sy = uniform(size_t(G) * 5, -1.0f, 1.0f, 38);
  const auto r = uniform(size_t(n) * 3, -1.0f, 1.0f, 39);  // L = Σ r · out
  auto b_sp = cl::Buffer::from(rt, sp), b_sx = cl::Buffer::from(rt, sx);
  auto b_sy = cl::Buffer::from(rt, sy), b_r = cl::Buffer::from(rt, r);
  cl::Buffer b_sout(rt, size_t(n) * 3 * 4), b_sgrad(rt, sp.size() * 4), b_sdy(rt, sy.size() * 4);
  field::MlpContext cr;
  smooth.forward(b_sp, 0, b_sx, n, b_sout, cr, &b_sy, 0, &index);
  smooth.backward(b_sp, 0, cr, b_sout, b_r, b_sgrad, 0, nullptr, &b_sdy);
  const auto sgrad = b_sgrad.read_vec<float>(sp.size());
  const auto sdy = b_sdy.read_vec<float>(sy.size());
  auto loss = [&](const std::vector<float>& p, const std::vector<float>& yv) {
    b_sp.write_vec(p);
    b_sy.write_vec(yv);
    field::MlpContext c2;
    smooth.forward(b_sp, 0, b_sx, n, b_sout, c2, &b_sy, 0, &index);
    return dot(b_sout.read_vec<float>(size_t(n) * 3), r);
  };
  std::vector<float> fd, an;
  central_diffs(sp, sgrad, every(sp.size(), 3, &sgrad), 1e-2f,
                [&](const std::vector<float>& p) { return loss(p, sy); }, fd, an);
  REQUIRE(fd.size() > 40);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
  fd.clear();
  an.clear();
  std::vector<size_t> which;
  for (size_t k = 0; k < sy.size(); ++k)
    if (k / 5 != 1 && k / 5 != 5) which.push_back(k);
  central_diffs(sy, sdy, which, 1e-2f, [&](const std::vector<float>& yv) { return loss(sp, yv); },
                fd, an);
  REQUIRE(fd.size() > 40);
  CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
  for (int c = 0; c < 5; ++c) CHECK(sdy[size_t(5) + c] == 0.0f);  // group 1 is empty
}

TEST_CASE("a bias-free MLP ignores its bias rows and gives them no gradient", "[field][mlp]") {
  auto& rt = test::runtime();
  auto spec = field::make_mlp_spec(16, 64, 2, 6, Activation::Relu);
  spec.bias = false;
  field::Mlp mlp(rt, spec);
  const int n = 333;
  std::vector<float> params(mlp.n_params());
  mlp.init_params(params, 0, 3);
  // Bias rows set to non-zero values: a biased MLP would read them.
  std::vector<size_t> bias_rows;
  for (size_t l = 0; l < spec.layers.size(); ++l) {
    const int in_l = l == 0 ? spec.n_in : spec.layers[l - 1].width;
    const int op = field::Mlp::pad16(spec.layers[l].width);
    for (int o = 0; o < spec.layers[l].width; ++o) {
      bias_rows.push_back(mlp.layer_offset(int(l)) + size_t(in_l) * op + o);
      params[bias_rows.back()] = 0.3f;
    }
  }
  auto zeroed = params;
  for (size_t k : bias_rows) zeroed[k] = 0.0f;
  const auto in = uniform(size_t(n) * 16, -1.0f, 1.0f, 4);
  const auto d_out = uniform(size_t(n) * 6, -1.0f, 1.0f, 5);
  auto b_p = cl::Buffer::from(rt, params), b_in = cl::Buffer::from(rt, in);
  auto b_d = cl::Buffer::from(rt, d_out);
  cl::Buffer b_out(rt, size_t(n) * 24), b_din(rt, size_t(n) * 64), b_g(rt, params.size() * 4);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_in, n, b_out, ctx);
  mlp.backward(b_p, 0, ctx, b_out, b_d, b_g, 0, &b_din);
  const auto out = b_out.read_vec<float>(size_t(n) * 6);
  auto grad = b_g.read_vec<float>(params.size());
  std::vector<float> din_ref;
  const auto out_ref = test::ref::mlp_fwd(spec, zeroed, in, n);
  auto g_ref = test::ref::mlp_bwd(spec, zeroed, in, n, d_out, din_ref);
  CHECK(norm_err(out, out_ref) < 1e-5);
  CHECK(norm_err(b_din.read_vec<float>(size_t(n) * 16), din_ref) < 1e-5);
  double bias_ref = 0;
  for (size_t k : bias_rows) {
    CHECK(grad[k] == 0.0f);
    bias_ref += std::fabs(g_ref[k]);
    g_ref[k] = 0.0f;
  }
  CHECK(bias_ref > 1e-3);  // a biased MLP's bias gradient would not be zero here
  CHECK(norm_err(grad, g_ref) < 1e-5);
  // The flag is what differs: the same parameters with biases read give another output.
  spec.bias = true;
  CHECK(norm_err(out, test::ref::mlp_fwd(spec, params, in, n)) > 1e-3);
}
