// MLP towers (MlpSpec::towers): one Mlp of T block-diagonal towers against T separate MLPs of
// 1/T the width (outputs, parameter gradients per block and zero off-block, d_in and
// d_group_in summed), init_params (zero off-block, towers = 1 unchanged), validate(), and
// Adam keeping the off-block weights at zero; the kernels that skip the zero blocks give the
// dense products' bits.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/error.hpp"
#include "core/rng.hpp"
#include "field/adam.hpp"
#include "field/mlp.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using field::Activation;

namespace {
using test::uniform;
using test::norm_err;
// The LiDAR head's shape with T towers of `tower_width`: 15 per-point features read from
// columns 1..15 of 16-wide rows, 24 grouped inputs, two hidden layers, T · `tower_out` outputs.
field::MlpSpec head_spec(int towers, int tower_width, int tower_out, Activation hidden,
                         Activation out) {
  field::MlpSpec s = field::make_mlp_spec(15, towers * tower_width, 2, towers * tower_out,
                                          hidden, out);
  s.n_in_group = 24;
  s.in_stride = 16;
  s.in_offset = 1;
  s.towers = towers;
  return s;
}
// The spec of one tower as a separate MLP.
field::MlpSpec tower_spec(const field::MlpSpec& s) {
  field::MlpSpec t = s;
  for (auto& l : t.layers) l.width /= s.towers;
  t.towers = 1;
  return t;
}
// Rows of layer l's weight block before the bias (the inputs, grouped ones included).
int rows(const field::MlpSpec& s, size_t l) {
  return l == 0 ? s.n_in + s.n_in_group : s.layers[l - 1].width;
}
// (index in the towers slice, index in tower t's separate slice) for every weight and bias of
// tower t: layer 0's column block, later layers' diagonal block, each with its bias entries.
std::vector<std::pair<size_t, size_t>> block(const field::Mlp& tw, const field::Mlp& sep, int t) {
  const auto& s = tw.spec();
  const int T = s.towers;
  std::vector<std::pair<size_t, size_t>> map;
  for (size_t l = 0; l < s.layers.size(); ++l) {
    const int r_tw = rows(s, l), r_s = l == 0 ? r_tw : r_tw / T;
    const int op_tw = field::Mlp::pad16(s.layers[l].width);
    const int out_s = s.layers[l].width / T, op_s = field::Mlp::pad16(out_s);
    const int i0 = l == 0 ? 0 : t * r_s, o0 = t * out_s;
    for (int i = 0; i <= r_s; ++i)
      for (int o = 0; o < out_s; ++o) {
        const int i_tw = i == r_s ? r_tw : i0 + i;  // the bias row follows the weights
        map.emplace_back(tw.layer_offset(int(l)) + size_t(i_tw) * op_tw + size_t(o0 + o),
                         sep.layer_offset(int(l)) + size_t(i) * op_s + size_t(o));
      }
  }
  return map;
}
// Whether k of the towers slice is in some tower's block (else: off-block or padding).
std::vector<bool> in_blocks(const field::Mlp& tw, const field::Mlp& sep) {
  std::vector<bool> in(tw.n_params(), false);
  for (int t = 0; t < tw.spec().towers; ++t)
    for (const auto& [k, ks] : block(tw, sep, t)) in[k] = true;
  return in;
}

// Runs the towers Mlp and its T separate towers (parameters copied from the blocks) on the
// same inputs, groups of `group` points, and checks they compute the same function.
void check_towers_equal_separate(const field::MlpSpec& spec, uint64_t seed) {
  auto& rt = test::runtime();
  const int T = spec.towers;
  const field::MlpSpec ss = tower_spec(spec);
  field::Mlp tw(rt, spec);
  std::vector<field::Mlp> sep;
  for (int t = 0; t < T; ++t) sep.emplace_back(rt, ss);
  const int G = 37, group = 13, n = G * group, no = spec.n_out(), no_s = ss.n_out();
  std::vector<float> p_tw(tw.n_params(), 0.0f);
  tw.init_params(p_tw, 0, seed);
  const auto in_block = in_blocks(tw, sep[0]);
  for (size_t l = 0; l < spec.layers.size(); ++l) {  // non-zero biases: the bias path is used
    const int op = field::Mlp::pad16(spec.layers[l].width);
    for (int o = 0; o < spec.layers[l].width; ++o)
      p_tw[tw.layer_offset(int(l)) + size_t(rows(spec, l)) * op + size_t(o)] = 0.03f * (o % 7 - 3);
  }
  std::vector<std::vector<float>> p_s(size_t(T), std::vector<float>(sep[0].n_params(), 0.0f));
  for (int t = 0; t < T; ++t)
    for (const auto& [k, ks] : block(tw, sep[0], t)) p_s[size_t(t)][ks] = p_tw[k];

  const auto x = uniform(size_t(n) * 16, -1.0f, 1.0f, seed + 1);
  const auto y = uniform(size_t(G) * 24, -1.0f, 1.0f, seed + 2);
  const auto d_out = uniform(size_t(n) * no, -1.0f, 1.0f, seed + 3);
  auto b_x = cl::Buffer::from(rt, x), b_y = cl::Buffer::from(rt, y);
  auto b_p = cl::Buffer::from(rt, p_tw), b_dout = cl::Buffer::from(rt, d_out);
  cl::Buffer b_out(rt, size_t(n) * no * 4);
  auto b_grad = cl::Buffer::from(rt, std::vector<float>(p_tw.size(), 9.0f));
  auto b_dx = cl::Buffer::from(rt, std::vector<float>(x.size(), 7.0f));
  cl::Buffer b_dy(rt, y.size() * 4);
  field::MlpContext ctx;
  tw.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, group);
  tw.backward(b_p, 0, ctx, b_out, b_dout, b_grad, 0, &b_dx, &b_dy);
  const auto out = b_out.read_vec<float>(size_t(n) * no);
  const auto grad = b_grad.read_vec<float>(p_tw.size());
  const auto dx = b_dx.read_vec<float>(x.size());
  const auto dy = b_dy.read_vec<float>(y.size());

  std::vector<float> dx_sum(size_t(n) * 15, 0.0f), dy_sum(y.size(), 0.0f);
  for (int t = 0; t < T; ++t) {
    std::vector<float> d_out_s(size_t(n) * no_s);
    for (int p = 0; p < n; ++p)
      for (int c = 0; c < no_s; ++c)
        d_out_s[size_t(p) * no_s + c] = d_out[size_t(p) * no + size_t(t * no_s + c)];
    auto b_ps = cl::Buffer::from(rt, p_s[size_t(t)]), b_ds = cl::Buffer::from(rt, d_out_s);
    cl::Buffer b_os(rt, size_t(n) * no_s * 4), b_gs(rt, p_s[size_t(t)].size() * 4);
    cl::Buffer b_dxs(rt, x.size() * 4), b_dys(rt, y.size() * 4);
    field::MlpContext cs;
    sep[size_t(t)].forward(b_ps, 0, b_x, n, b_os, cs, &b_y, group);
    sep[size_t(t)].backward(b_ps, 0, cs, b_os, b_ds, b_gs, 0, &b_dxs, &b_dys);
    const auto out_s = b_os.read_vec<float>(size_t(n) * no_s);
    const auto grad_s = b_gs.read_vec<float>(p_s[size_t(t)].size());
    const auto dxs = b_dxs.read_vec<float>(x.size());
    const auto dys = b_dys.read_vec<float>(y.size());
    std::vector<float> out_t;  // tower t's columns of the towers output
    for (int p = 0; p < n; ++p)
      for (int c = 0; c < no_s; ++c) out_t.push_back(out[size_t(p) * no + size_t(t * no_s + c)]);
    INFO("tower " << t);
    CHECK(norm_err(out_t, out_s) < 1e-5);
    std::vector<float> g_tw, g_s;
    for (const auto& [k, ks] : block(tw, sep[0], t)) {
      g_tw.push_back(grad[k]);
      g_s.push_back(grad_s[ks]);
    }
    CHECK(norm_err(g_tw, g_s) < 1e-5);
    CHECK(test::max_sym_rel_err(g_tw, g_s, 1e-3) < 1e-4);
    for (int p = 0; p < n; ++p)
      for (int c = 0; c < 15; ++c) dx_sum[size_t(p) * 15 + c] += dxs[size_t(p) * 16 + 1 + c];
    for (size_t k = 0; k < dy_sum.size(); ++k) dy_sum[k] += dys[k];
  }
  // Off-block weights (and padding) get exactly zero gradient: Adam leaves them at zero.
  size_t off_block = 0, nonzero = 0;
  for (size_t k = 0; k < grad.size(); ++k)
    if (!in_block[k]) {
      ++off_block;
      nonzero += grad[k] != 0.0f;
    }
  CHECK(off_block > 0);
  CHECK(nonzero == 0);
  std::vector<float> dx_tw;
  size_t untouched = 0;
  for (int p = 0; p < n; ++p) {
    untouched += dx[size_t(p) * 16] == 7.0f;  // column 0 is not the MLP's input
    for (int c = 0; c < 15; ++c) dx_tw.push_back(dx[size_t(p) * 16 + 1 + c]);
  }
  CHECK(untouched == size_t(n));
  CHECK(norm_err(dx_tw, dx_sum) < 1e-5);
  CHECK(norm_err(dy, dy_sum) < 1e-5);
}

// Mlp::init_params as it was before towers: one draw per slot of Rng(seed, 0x4d4c), bound
// √(gain / fan_in) with fan_in the rows before the bias, zero bias and padding.
std::vector<float> init_before_towers(const field::MlpSpec& s, const field::Mlp& mlp,
                                      uint64_t seed) {
  std::vector<float> p(mlp.n_params(), 0.0f);
  Rng rng(seed, 0x4d4cu);
  for (size_t l = 0; l < s.layers.size(); ++l) {
    const int r = rows(s, l), out = s.layers[l].width, op = field::Mlp::pad16(out);
    const double gain = s.layers[l].activation == Activation::Relu ? 6.0 : 3.0;
    const float bound = float(std::sqrt(gain / r));
    for (int i = 0; i <= r; ++i)
      for (int o = 0; o < op; ++o) {
        const float u = rng.uniform(-bound, bound);
        p[mlp.layer_offset(int(l)) + size_t(i) * op + size_t(o)] = (i < r && o < out) ? u : 0.0f;
      }
  }
  return p;
}
}  // namespace

TEST_CASE("an MLP of towers computes the separate MLPs with their gradients",
          "[field][mlp][towers]") {
  SECTION("LiDAR head: 2 towers of 2x64 relu, one linear output each") {
    check_towers_equal_separate(head_spec(2, 64, 1, Activation::Relu, Activation::None), 41);
  }
  SECTION("4 towers of 2x12 tanh, two softplus outputs each (pre-activations kept)") {
    check_towers_equal_separate(head_spec(4, 12, 2, Activation::Tanh, Activation::Softplus), 42);
  }
}

TEST_CASE("towers init: zero off-block, tower fan-in, towers = 1 unchanged",
          "[field][mlp][towers]") {
  auto& rt = test::runtime();
  // towers = 1 (unset or explicit) draws exactly what the init drew before towers existed.
  for (const auto& s1 : {head_spec(1, 64, 2, Activation::Relu, Activation::None),
                         head_spec(1, 20, 3, Activation::Tanh, Activation::Sine)}) {
    field::MlpSpec unset = s1;
    unset.towers = field::MlpSpec{}.towers;
    field::Mlp m1(rt, s1), mu(rt, unset);
    std::vector<float> p1(m1.n_params()), pu(mu.n_params());
    m1.init_params(p1, 0, 7);
    mu.init_params(pu, 0, 7);
    CHECK(p1 == init_before_towers(s1, m1, 7));
    CHECK(pu == p1);
  }
  const field::MlpSpec spec = head_spec(2, 64, 1, Activation::Relu, Activation::None);
  field::MlpSpec dense = spec;
  dense.towers = 1;
  field::Mlp tw(rt, spec), sep(rt, tower_spec(spec)), dn(rt, dense);
  REQUIRE(tw.n_params() == dn.n_params());  // same layout as the dense MLP
  const size_t off = 5;
  std::vector<float> p(off + tw.n_params(), 3.0f), pd(dn.n_params());
  tw.init_params(p, off, 9);
  dn.init_params(pd, 0, 9);
  CHECK(p[off - 1] == 3.0f);  // outside the slice: untouched
  const auto in_block = in_blocks(tw, sep);
  size_t off_nonzero = 0, on_zero = 0, out_of_bound = 0, off_count = 0;
  for (size_t l = 0; l < spec.layers.size(); ++l) {
    const int r = rows(spec, l), out = spec.layers[l].width, op = field::Mlp::pad16(out);
    const int fan_in = l == 0 ? r : r / spec.towers;  // layer 0 is dense
    const float bound = float(std::sqrt((l + 1 < spec.layers.size() ? 6.0 : 3.0) / fan_in));
    for (int i = 0; i <= r; ++i)
      for (int o = 0; o < op; ++o) {
        const size_t k = tw.layer_offset(int(l)) + size_t(i) * op + size_t(o);
        const float w = p[off + k];
        if (i == r || o >= out) {
          CHECK(w == 0.0f);  // bias and padding
        } else if (!in_block[k]) {
          ++off_count;
          off_nonzero += w != 0.0f;
        } else {
          on_zero += w == 0.0f;
          out_of_bound += std::fabs(w) > bound;
        }
      }
  }
  CHECK(off_count == size_t(2 * 64 * 64 + 2 * 64));  // layer 1's 2 blocks, the output's 2
  CHECK(off_nonzero == 0);
  CHECK(on_zero == 0);
  CHECK(out_of_bound == 0);
  // Layer 0 is dense: the same values as the dense MLP's (the stream is layout-stable).
  const size_t l1 = tw.layer_offset(1);
  CHECK(std::equal(p.begin() + off, p.begin() + off + l1, pd.begin()));
}

TEST_CASE("towers: widths must divide into the towers", "[field][mlp][towers]") {
  field::MlpSpec ok = head_spec(2, 64, 1, Activation::Relu, Activation::None);
  CHECK_NOTHROW(ok.validate());
  auto bad = ok;
  bad.layers[1].width = 127;  // a hidden width
  CHECK_THROWS_AS(bad.validate(), ConfigError);
  bad = ok;
  bad.layers.back().width = 3;  // the output width
  CHECK_THROWS_AS(bad.validate(), ConfigError);
  bad = ok;
  bad.towers = 0;
  CHECK_THROWS_AS(bad.validate(), ConfigError);
  bad = ok;
  bad.towers = -2;
  CHECK_THROWS_AS(bad.validate(), ConfigError);
  bad = field::make_mlp_spec(8, 72, 1, 9, Activation::Relu);
  bad.towers = 9;  // widths divisible, but more than 8 towers
  CHECK_THROWS_AS(bad.validate(), ConfigError);
  bad.towers = 3;
  CHECK_NOTHROW(bad.validate());
}

TEST_CASE("Adam keeps the off-block weights of towers at zero", "[field][mlp][towers]") {
  auto& rt = test::runtime();
  const field::MlpSpec spec = head_spec(2, 64, 1, Activation::Relu, Activation::None);
  field::Mlp tw(rt, spec), sep(rt, tower_spec(spec));
  const int G = 20, group = 16, n = G * group;
  std::vector<float> p(tw.n_params());
  tw.init_params(p, 0, 13);
  const auto in_block = in_blocks(tw, sep);
  auto b_p = cl::Buffer::from(rt, p);
  auto b_x = cl::Buffer::from(rt, uniform(size_t(n) * 16, -1.0f, 1.0f, 14));
  auto b_y = cl::Buffer::from(rt, uniform(size_t(G) * 24, -1.0f, 1.0f, 15));
  cl::Buffer b_out(rt, size_t(n) * 2 * 4), b_d(rt, size_t(n) * 2 * 4), b_g(rt, p.size() * 4);
  field::AdamConfig cfg;
  cfg.weight_decay = 1e-3f;  // the L2 term of a zero weight is zero too
  field::Adam adam(rt, p.size(), cfg);
  for (int step = 0; step < 3; ++step) {
    b_d.write_vec(uniform(size_t(n) * 2, -1.0f, 1.0f, 16 + uint64_t(step)));
    field::MlpContext ctx;
    tw.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, group);
    tw.backward(b_p, 0, ctx, b_out, b_d, b_g, 0);
    adam.begin_step();
    adam.update(b_p, b_g, 0, p.size(), 1e-2f);
  }
  const auto q = b_p.read_vec<float>(p.size());
  size_t off_nonzero = 0, on_changed = 0, on_count = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    if (!in_block[k]) {
      off_nonzero += q[k] != 0.0f;
    } else {
      ++on_count;
      on_changed += q[k] != p[k];
    }
  }
  CHECK(off_nonzero == 0);
  CHECK(on_changed > on_count * 9 / 10);  // the towers themselves did train
}

namespace {
// The towers Mlp (whose kernels skip the zero blocks where a tile lies in one tower) against
// an Mlp of the same widths computed dense (towers = 1) on the same parameters, zero off the
// blocks: outputs, d_in, d_group_in and the in-block gradient must be the same bits (a skipped
// term is an exact x · 0).
void check_towers_skip_exact(const field::MlpSpec& spec, uint64_t seed) {
  auto& rt = test::runtime();
  field::MlpSpec dense_spec = spec;
  dense_spec.towers = 1;
  field::Mlp tw(rt, spec), dense(rt, dense_spec), sep(rt, tower_spec(spec));
  REQUIRE(tw.n_params() == dense.n_params());
  const int G = 19, group = 16, n = G * group, no = spec.n_out();
  std::vector<float> p(tw.n_params());
  tw.init_params(p, 0, seed);
  const auto in_block = in_blocks(tw, sep);
  auto b_p = cl::Buffer::from(rt, p);
  auto b_x = cl::Buffer::from(rt, uniform(size_t(n) * 16, -1.0f, 1.0f, seed + 1));
  auto b_y = cl::Buffer::from(rt, uniform(size_t(G) * 24, -1.0f, 1.0f, seed + 2));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * no, -1.0f, 1.0f, seed + 3));
  struct Pass {
    std::vector<float> out, grad, dx, dy;
  };
  auto run = [&](field::Mlp& m) {
    cl::Buffer b_out(rt, size_t(n) * no * 4), b_g(rt, p.size() * 4);
    auto b_dx = cl::Buffer::from(rt, std::vector<float>(size_t(n) * 16, 0.0f));
    cl::Buffer b_dy(rt, size_t(G) * 24 * 4);
    field::MlpContext ctx;
    m.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, group);
    m.backward(b_p, 0, ctx, b_out, b_d, b_g, 0, &b_dx, &b_dy);
    return Pass{b_out.read_vec<float>(size_t(n) * no), b_g.read_vec<float>(p.size()),
                b_dx.read_vec<float>(size_t(n) * 16), b_dy.read_vec<float>(size_t(G) * 24)};
  };
  const Pass a = run(tw), b = run(dense);
  CHECK(a.out == b.out);
  CHECK(a.dx == b.dx);
  CHECK(a.dy == b.dy);
  size_t in_diff = 0, in_count = 0, off_nonzero_dense = 0;
  for (size_t k = 0; k < p.size(); ++k) {
    if (in_block[k]) {
      ++in_count;
      in_diff += a.grad[k] != b.grad[k];
    } else {
      off_nonzero_dense += b.grad[k] != 0.0f;
    }
  }
  CHECK(in_count > 0);
  CHECK(in_diff == 0);
  CHECK(off_nonzero_dense > 0);  // the dense pass does compute the off-block gradient
}
}  // namespace

TEST_CASE("towers skip their zero blocks with the dense products' results",
          "[field][mlp][towers]") {
  SECTION("2 towers of 2x64 (16-aligned: every hidden tile skips)") {
    check_towers_skip_exact(head_spec(2, 64, 1, Activation::Relu, Activation::None), 51);
  }
  SECTION("4 towers of 2x32, two softplus outputs each") {
    check_towers_skip_exact(head_spec(4, 32, 2, Activation::Tanh, Activation::Softplus), 52);
  }
  SECTION("2 towers of 2x24 (tiles straddle towers: computed dense)") {
    check_towers_skip_exact(head_spec(2, 24, 1, Activation::Relu, Activation::None), 53);
  }
}
