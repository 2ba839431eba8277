// The MLP's local_tiles GEMMs (device profile gemm = "local_tiles", the "gpu" profile's;
// kernels/field/mlp_tiles.cl) on the test device: the host reference with the profile's
// register block and with the 1 x 1 block of small launches (bit-identical to each other, as
// every sum keeps its order), bit-reproducible, within float rounding of the cpu_tiles
// kernels; every feature define (column offsets, grouped inputs by size and by index, towers
// skipping and straddling, bias-free, kept pre-activations) against cpu_tiles; finite
// differences of the device forward; and the work-items of each launch at the flow MLP's
// batch (pipeline_parallelism's rule). The other MLP cases run under the gpu profile too: ctest
// field_mlp_gpu_profile (tests/field/CMakeLists.txt).
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include "cl/launch_trace.hpp"
#include "field/mlp.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"
#include "support/gemm_profiles.hpp"
#include "support/device_tolerance.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using sgnlf::test::same_bits;
using sgnlf::test::tiles_profile;
using sgnlf::test::cpu_tiles_profile;
using field::Activation;

namespace {
using test::norm_err;
using test::uniform;

// Sets the shared Runtime's device profile for a scope (an Mlp reads it when it is made).
class ScopedProfile {
 public:
  explicit ScopedProfile(const cl::DeviceProfile& p) : saved_(test::runtime().device_profile()) {
    test::runtime().set_device_profile(p);
  }
  ~ScopedProfile() { test::runtime().set_device_profile(saved_); }
  ScopedProfile(const ScopedProfile&) = delete;
  ScopedProfile& operator=(const ScopedProfile&) = delete;

 private:
  cl::DeviceProfile saved_;
};

// The gpu profile; `block` 0: the 1 x 1 block everywhere, 1: the profile's block everywhere.
double dot(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += double(a[i]) * b[i];
  return s;
}

// One forward and backward: the output, the parameter gradient slice, d_in and d_group_in.
struct Pass {
  std::vector<float> out, grad, d_in, d_group;
};
struct Inputs {
  int n = 0, groups = 0;  // groups: rows of the grouped input (0: none)
  std::vector<float> params, x, y, d_out;
  std::vector<int32_t> offsets, point_group;  // a group index when not empty
};
Pass run(const cl::DeviceProfile& profile, const field::MlpSpec& spec, const Inputs& d) {
  auto& rt = test::runtime();
  ScopedProfile scoped(profile);
  field::Mlp mlp(rt, spec);
  const int n = d.n, no = spec.n_out(), stride = spec.row_stride();
  auto b_p = cl::Buffer::from(rt, d.params), b_x = cl::Buffer::from(rt, d.x);
  auto b_dout = cl::Buffer::from(rt, d.d_out);
  cl::Buffer b_out(rt, size_t(n) * no * 4);
  auto b_grad = cl::Buffer::from(rt, std::vector<float>(d.params.size(), 9.0f));
  auto b_dx = cl::Buffer::from(rt, std::vector<float>(size_t(n) * stride, 7.0f));
  field::MlpContext ctx;
  Pass r;
  if (spec.n_in_group > 0) {
    auto b_y = cl::Buffer::from(rt, d.y);
    cl::Buffer b_dy(rt, d.y.size() * 4);
    if (!d.offsets.empty()) {
      auto b_pg = cl::Buffer::from(rt, d.point_group), b_off = cl::Buffer::from(rt, d.offsets);
      const field::GroupIndex index{&b_pg, &b_off, d.groups};
      mlp.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, 0, &index);
      mlp.backward(b_p, 0, ctx, b_out, b_dout, b_grad, 0, &b_dx, &b_dy);
      r.d_group = b_dy.read_vec<float>(d.y.size());
    } else {
      mlp.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, n / d.groups);
      mlp.backward(b_p, 0, ctx, b_out, b_dout, b_grad, 0, &b_dx, &b_dy);
      r.d_group = b_dy.read_vec<float>(d.y.size());
    }
  } else {
    mlp.forward(b_p, 0, b_x, n, b_out, ctx);
    mlp.backward(b_p, 0, ctx, b_out, b_dout, b_grad, 0, &b_dx);
  }
  r.out = b_out.read_vec<float>(size_t(n) * no);
  r.grad = b_grad.read_vec<float>(d.params.size());
  r.d_in = b_dx.read_vec<float>(size_t(n) * stride);
  return r;
}

// The slice indices of every layer's bias row (its padding included; mlp.hpp's layout).
std::vector<size_t> bias_rows(const field::MlpSpec& spec) {
  std::vector<size_t> k;
  size_t off = 0;
  int rows = spec.n_in + spec.n_in_group;
  for (const auto& layer : spec.layers) {
    const int op = field::Mlp::pad16(layer.width);
    for (int o = 0; o < op; ++o) k.push_back(off + size_t(rows) * op + size_t(o));
    off += size_t(rows + 1) * op;
    rows = layer.width;
  }
  return k;
}

// Inputs for `spec`: init_params, non-zero biases (the bias path is used; a bias-free MLP must
// ignore them), uniform inputs and output gradients.
Inputs make_inputs(const field::MlpSpec& spec, int n, int groups, uint64_t seed) {
  ScopedProfile scoped(cl::gpu_profile());
  field::Mlp mlp(test::runtime(), spec);
  Inputs d;
  d.n = n;
  d.groups = groups;
  d.params.assign(mlp.n_params(), 0.0f);
  mlp.init_params(d.params, 0, seed);
  for (size_t l = 0; l < spec.layers.size(); ++l) {
    const int rows = l == 0 ? spec.n_in + spec.n_in_group : spec.layers[l - 1].width;
    const int op = field::Mlp::pad16(spec.layers[l].width);
    for (int o = 0; o < spec.layers[l].width; ++o)
      d.params[mlp.layer_offset(int(l)) + size_t(rows) * op + size_t(o)] = 0.05f * (o % 5 - 2);
  }
  d.x = uniform(size_t(n) * spec.row_stride(), -1.0f, 1.0f, seed + 1);
  d.y = uniform(size_t(groups) * spec.n_in_group, -1.0f, 1.0f, seed + 2);
  d.d_out = uniform(size_t(n) * spec.n_out(), -1.0f, 1.0f, seed + 3);
  return d;
}

field::MlpSpec odd_spec() {  // widths not multiples of 16, every activation
  field::MlpSpec s;
  s.n_in = 5;
  s.layers = {{20, Activation::Softplus}, {33, Activation::Sine}, {7, Activation::Tanh},
              {3, Activation::Relu}, {2, Activation::Tanh}};
  return s;
}
field::MlpSpec wide_spec() {  // 128 and 80 outputs: two column tiles of 64, one partial
  field::MlpSpec s;
  s.n_in = 100;
  s.layers = {{128, Activation::Relu}, {80, Activation::Tanh}, {3, Activation::None}};
  return s;
}
}  // namespace

TEST_CASE("local_tiles MLP GEMMs match the host reference with either register block",
          "[field][mlp_tiles]") {
  struct Case {
    const char* name;
    field::MlpSpec spec;
  };
  auto bias_free = field::make_mlp_spec(16, 64, 2, 6, Activation::Relu);
  bias_free.bias = false;
  const Case cases[] = {{"density 32-64-16", field::make_mlp_spec(32, 64, 1, 16, Activation::Relu)},
                        {"head 87-64x3-2", field::make_mlp_spec(87, 64, 3, 2, Activation::Relu)},
                        {"psi sine", field::make_mlp_spec(3, 64, 2, 16, Activation::Sine)},
                        {"odd widths", odd_spec()},
                        {"wide 100-128-80-3", wide_spec()},
                        {"bias-free 16-64x2-6", bias_free}};
  const int n = 333;  // not a multiple of any tile; 6 weight-gradient chunks, the last partial
  for (const auto& c : cases) {
    SECTION(c.name) {
      const Inputs d = make_inputs(c.spec, n, 0, 5);
      // The reference's layers all have biases: a bias-free MLP is the reference with zero
      // biases (its non-zero bias rows unread) and no gradient to them.
      auto ref_params = d.params;
      if (!c.spec.bias)
        for (size_t k : bias_rows(c.spec)) ref_params[k] = 0.0f;
      std::vector<float> din_ref;
      const auto out_ref = test::ref::mlp_fwd(c.spec, ref_params, d.x, n);
      auto g_ref = test::ref::mlp_bwd(c.spec, ref_params, d.x, n, d.d_out, din_ref);
      if (!c.spec.bias)
        for (size_t k : bias_rows(c.spec)) g_ref[k] = 0.0f;
      const Pass small = run(tiles_profile(0), c.spec, d);
      const Pass main = run(tiles_profile(1), c.spec, d);
      for (const Pass* p : {&small, &main}) {
        INFO((p == &small ? "1 x 1 block" : "profile's block"));
        CHECK(norm_err(p->out, out_ref) < 1e-5);
        CHECK(norm_err(p->grad, g_ref) < 1e-5);
        CHECK(test::max_sym_rel_err(p->grad, g_ref, 1.0) < 1e-4);
        CHECK(norm_err(p->d_in, din_ref) < 1e-5);
      }
      // Each sum keeps its order whatever the block: the same bits.
      CHECK(same_bits(small.out, main.out));
      CHECK(same_bits(small.grad, main.grad));
      CHECK(same_bits(small.d_in, main.d_in));
      // Bit-reproducible from run to run; within float rounding of the cpu_tiles kernels.
      const Pass again = run(tiles_profile(1), c.spec, d);
      CHECK(same_bits(again.out, main.out));
      CHECK(same_bits(again.grad, main.grad));
      CHECK(same_bits(again.d_in, main.d_in));
      const Pass cpu = run(cpu_tiles_profile(), c.spec, d);
      CHECK(norm_err(main.out, cpu.out) < 1e-5);
      CHECK(norm_err(main.grad, cpu.grad) < 1e-5);
      CHECK(norm_err(main.d_in, cpu.d_in) < 1e-5);
    }
  }
}

TEST_CASE("local_tiles keep every MLP feature: offsets, groups, towers, bias-free, pre-activations",
          "[field][mlp_tiles]") {
  // Against cpu_tiles (tested against the references and the plain MLPs in test_mlp.cpp and
  // test_mlp_towers.cpp) on the same inputs, with either register block.
  struct Case {
    const char* name;
    field::MlpSpec spec;
    std::vector<int> group_sizes;  // empty: equal groups of 7
  };
  // The LiDAR head's layout: 15 columns at offset 1 of 16-wide rows, 24 grouped inputs.
  auto head = [](int towers, int width, int out, Activation hidden, Activation last) {
    field::MlpSpec s = field::make_mlp_spec(15, towers * width, 2, towers * out, hidden, last);
    s.n_in_group = 24;
    s.in_stride = 16;
    s.in_offset = 1;
    s.towers = towers;
    return s;
  };
  auto flow = field::make_mlp_spec(16, 64, 2, 6, Activation::Relu);  // LiDAR4D's flow MLP
  flow.bias = false;
  const Case cases[] = {
      // Sine hidden layers keep pre-activations (STORE_PRE, PREV_PRE), softplus output too.
      {"2 towers of 2x32 sine, softplus outputs, indexed groups",
       head(2, 32, 2, Activation::Sine, Activation::Softplus), {5, 0, 17, 1, 9, 0, 33, 2, 8, 21, 3}},
      // 64-wide towers: every 64-column tile lies in one tower (the zero blocks skipped).
      {"2 towers of 2x64 relu, equal groups", head(2, 64, 1, Activation::Relu, Activation::None), {}},
      // 24-wide towers: tiles straddle towers and compute the dense products.
      {"2 towers of 2x24 tanh, equal groups", head(2, 24, 2, Activation::Tanh, Activation::Tanh), {}},
      {"flow MLP, bias-free", flow, {}}};
  for (const auto& c : cases) {
    SECTION(c.name) {
      const bool grouped = c.spec.n_in_group > 0;
      const bool indexed = !c.group_sizes.empty();
      const int groups = !grouped ? 0 : indexed ? int(c.group_sizes.size()) : 31;
      int n = 217;
      if (grouped) n = indexed ? 0 : groups * 7;
      for (int s : c.group_sizes) n += s;
      Inputs d = make_inputs(c.spec, n, groups, 11);
      if (indexed) {
        d.offsets = {0};
        for (int g = 0; g < groups; ++g) {
          d.offsets.push_back(d.offsets.back() + c.group_sizes[size_t(g)]);
          for (int k = 0; k < c.group_sizes[size_t(g)]; ++k) d.point_group.push_back(g);
        }
      }
      const Pass cpu = run(cpu_tiles_profile(), c.spec, d);
      const Pass small = run(tiles_profile(0), c.spec, d);
      const Pass main = run(tiles_profile(1), c.spec, d);
      for (const Pass* p : {&small, &main}) {
        INFO((p == &small ? "1 x 1 block" : "profile's block"));
        CHECK(norm_err(p->out, cpu.out) < 1e-5);
        CHECK(norm_err(p->grad, cpu.grad) < 1e-5);
        CHECK(test::max_sym_rel_err(p->grad, cpu.grad, 1.0) < 1e-4);
        // d_in in the input's columns, others untouched (7); d_group_in.
        CHECK(norm_err(p->d_in, cpu.d_in) < 1e-5);
        if (grouped) CHECK(norm_err(p->d_group, cpu.d_group) < 1e-5);
        size_t zero_where_cpu_zero = 0, cpu_zero = 0;  // padding, off-tower, bias-free rows
        for (size_t k = 0; k < cpu.grad.size(); ++k)
          if (cpu.grad[k] == 0.0f) {
            ++cpu_zero;
            zero_where_cpu_zero += p->grad[k] == 0.0f;
          }
        CHECK(zero_where_cpu_zero == cpu_zero);
      }
      CHECK(same_bits(small.out, main.out));
      CHECK(same_bits(small.grad, main.grad));
      CHECK(same_bits(small.d_in, main.d_in));
      CHECK(same_bits(small.d_group, main.d_group));
      if (c.spec.in_offset > 0)
        for (int p = 0; p < n; ++p) CHECK(main.d_in[size_t(p) * 16] == 7.0f);
    }
  }
}

TEST_CASE("local_tiles MLP gradients agree with finite differences of the device forward",
          "[field][mlp_tiles][fd]") {
  // Smooth activations, grouped inputs at a column offset, two towers, kept pre-activations.
  field::MlpSpec spec;
  spec.n_in = 4;
  spec.n_in_group = 5;
  spec.in_stride = 6;
  spec.in_offset = 2;
  spec.towers = 2;
  spec.layers = {{24, Activation::Tanh}, {18, Activation::Sine}, {4, Activation::Softplus}};
  const int G = 6, group = 4, n = G * group, no = spec.n_out();
  const Inputs d = make_inputs(spec, n, G, 21);
  for (int block = 0; block < 2; ++block) {
    INFO((block == 0 ? "1 x 1 block" : "profile's block"));
    auto& rt = test::runtime();
    ScopedProfile scoped(tiles_profile(block));
    field::Mlp mlp(rt, spec);
    auto b_p = cl::Buffer::from(rt, d.params), b_x = cl::Buffer::from(rt, d.x);
    auto b_y = cl::Buffer::from(rt, d.y), b_r = cl::Buffer::from(rt, d.d_out);  // L = Σ r · out
    cl::Buffer b_out(rt, size_t(n) * no * 4), b_dx(rt, d.x.size() * 4), b_dy(rt, d.y.size() * 4),
        b_grad(rt, d.params.size() * 4);
    field::MlpContext ctx;
    mlp.forward(b_p, 0, b_x, n, b_out, ctx, &b_y, group);
    mlp.backward(b_p, 0, ctx, b_out, b_r, b_grad, 0, &b_dx, &b_dy);
    const auto grad = b_grad.read_vec<float>(d.params.size());
    const auto dx = b_dx.read_vec<float>(d.x.size()), dy = b_dy.read_vec<float>(d.y.size());
    auto loss = [&](const std::vector<float>& p, const std::vector<float>& xv,
                    const std::vector<float>& yv) {
      b_p.write_vec(p);
      b_x.write_vec(xv);
      b_y.write_vec(yv);
      field::MlpContext c2;
      mlp.forward(b_p, 0, b_x, n, b_out, c2, &b_y, group);
      return dot(b_out.read_vec<float>(size_t(n) * no), d.d_out);
    };
    const float h = 1e-2f;
    // Central differences: truncation O(h²·f''') ~1e-4, float rounding of L ~1e-6/h.
    auto check = [&](const std::vector<float>& v, const std::vector<float>& an_all,
                     const std::vector<size_t>& which, auto with) {
      std::vector<float> fd, an;
      for (size_t k : which) {
        auto vp = v, vm = v;
        vp[k] += h;
        vm[k] -= h;
        fd.push_back(float((with(vp) - with(vm)) / (2.0 * h)));
        an.push_back(an_all[k]);
      }
      REQUIRE(fd.size() > 20);
      CHECK(test::max_sym_rel_err(fd, an, 1e-1) < 5e-3);
    };
    std::vector<size_t> params_k, x_k, y_k;
    for (size_t k = 0; k < grad.size(); k += 3)
      if (grad[k] != 0.0f) params_k.push_back(k);  // not padding or off-tower
    for (int p = 0; p < n; ++p)
      for (int c = 0; c < 4; ++c) x_k.push_back(size_t(p) * 6 + 2 + size_t(c));
    for (size_t k = 0; k < d.y.size(); ++k) y_k.push_back(k);
    check(d.params, grad, params_k, [&](const std::vector<float>& p) { return loss(p, d.x, d.y); });
    check(d.x, dx, x_k, [&](const std::vector<float>& x) { return loss(d.params, x, d.y); });
    check(d.y, dy, y_k, [&](const std::vector<float>& y) { return loss(d.params, d.x, y); });
  }
}

TEST_CASE("local_tiles launches at the flow MLP's batch are wide enough for a GPU",
          "[field][mlp_tiles]") {
  // LiDAR4D's flow MLP (16 -> 64 -> 64 -> 6, bias-free) on the 2304 points of one quick step:
  // pipeline_parallelism's rule asks >= 1e4 work-items of a kernel over > 1e5 elements, and
  // every GEMM here reads the flat parameter buffer. The profile's 4 x 4 block would give
  // 2304-9216; the 1 x 1 block takes over below gemm_min_work_items.
  auto& rt = test::runtime();
  auto spec = field::make_mlp_spec(16, 64, 2, 6, Activation::Relu);
  spec.bias = false;
  const int n = 2304;
  ScopedProfile scoped(cl::gpu_profile());
  field::Mlp mlp(rt, spec);
  std::vector<float> params(mlp.n_params());
  mlp.init_params(params, 0, 3);
  auto b_p = cl::Buffer::from(rt, params);
  auto b_x = cl::Buffer::from(rt, uniform(size_t(n) * 16, -1.0f, 1.0f, 4));
  auto b_d = cl::Buffer::from(rt, uniform(size_t(n) * 6, -1.0f, 1.0f, 5));
  cl::Buffer b_out(rt, size_t(n) * 6 * 4), b_g(rt, params.size() * 4), b_dx(rt, size_t(n) * 64);
  field::MlpContext ctx;
  mlp.forward(b_p, 0, b_x, n, b_out, ctx);  // builds the programs
  mlp.backward(b_p, 0, ctx, b_out, b_d, b_g, 0, &b_dx);
  rt.finish();
  cl::LaunchTrace trace;
  rt.set_trace(&trace);
  mlp.forward(b_p, 0, b_x, n, b_out, ctx);
  mlp.backward(b_p, 0, ctx, b_out, b_d, b_g, 0, &b_dx);
  rt.set_trace(nullptr);
  rt.finish();
  std::string shapes;
  size_t gemms = 0;
  for (const auto& l : trace.launches) {
    shapes += l.kernel + " " + std::to_string(l.work_items) + "\n";
    gemms += l.kernel == "field_mlp_fwd" || l.kernel == "field_mlp_bwd_in" ||
             l.kernel == "field_mlp_bwd_wgt";
    CHECK(l.kernel != "field_mlp_transpose");
  }
  INFO(shapes);
  CHECK(gemms == 3 + 3 + 3);
  for (const auto& l : trace.launches) CHECK(l.work_items >= 10000);
}

TEST_CASE("local_tiles at small sizes: both blocks against the reference and cpu_tiles",
          "[field][mlp_tiles][small]") {
  // Sized for Oclgrind (the label oclgrind_field: out-of-bounds accesses, data races, barrier
  // divergence): 37 points, layers of at most 33; 16-column tiles, so that 32-wide layers take
  // two column tiles, work-groups of 64 and a 2 x 4 block (tiles of 32 rows: one full, one
  // partial), and chunks of 8 points (five weight-gradient chunks, the last partial).
  cl::DeviceProfile small_tiles = cl::gpu_profile();
  small_tiles.gemm_tile = 16;
  small_tiles.gemm_work_group = 64;
  small_tiles.gemm_block_rows = 2;
  small_tiles.gemm_chunk_points = 8;
  cl::DeviceProfile one_by_one = small_tiles;
  small_tiles.gemm_min_work_items = 0;
  one_by_one.gemm_min_work_items = 1 << 30;
  const int n = 37;
  SECTION("odd widths, every activation but relu, against the host reference") {
    field::MlpSpec spec;
    spec.n_in = 5;
    spec.layers = {{20, Activation::Softplus}, {33, Activation::Sine}, {3, Activation::Tanh}};
    const Inputs d = make_inputs(spec, n, 0, 7);
    std::vector<float> din_ref;
    const auto out_ref = test::ref::mlp_fwd(spec, d.params, d.x, n);
    const auto g_ref = test::ref::mlp_bwd(spec, d.params, d.x, n, d.d_out, din_ref);
    const Pass a = run(small_tiles, spec, d), b = run(one_by_one, spec, d);
    CHECK(norm_err(a.out, out_ref) < 1e-5);
    CHECK(norm_err(a.grad, g_ref) < 1e-5);
    CHECK(norm_err(a.d_in, din_ref) < 1e-5);
    CHECK(same_bits(a.out, b.out));
    CHECK(same_bits(a.grad, b.grad));
    CHECK(same_bits(a.d_in, b.d_in));
  }
  struct Case {
    const char* name;
    field::MlpSpec spec;
  };
  field::MlpSpec grouped;  // columns 2..6 of 8-wide rows, 6 grouped inputs, 2 towers of 16
  grouped.n_in = 5;
  grouped.in_stride = 8;
  grouped.in_offset = 2;
  grouped.n_in_group = 6;
  grouped.towers = 2;
  grouped.layers = {{32, Activation::Sine}, {32, Activation::Relu}, {4, Activation::Softplus}};
  field::MlpSpec straddle = field::make_mlp_spec(6, 16, 2, 2, Activation::Tanh);
  straddle.towers = 2;  // towers of 8 in 16-column tiles: computed dense
  straddle.bias = false;
  for (const Case& c : {Case{"grouped by index, offset columns, towers skipping", grouped},
                        Case{"towers straddling a tile, bias-free", straddle}}) {
    SECTION(c.name) {
      const bool has_groups = c.spec.n_in_group > 0;
      const std::vector<int> sizes = {5, 0, 9, 1, 13, 0, 6, 3};  // 37 points
      Inputs d = make_inputs(c.spec, n, has_groups ? int(sizes.size()) : 0, 9);
      if (has_groups) {
        d.offsets = {0};
        for (size_t g = 0; g < sizes.size(); ++g) {
          d.offsets.push_back(d.offsets.back() + sizes[g]);
          for (int k = 0; k < sizes[g]; ++k) d.point_group.push_back(int32_t(g));
        }
      }
      const Pass cpu = run(cpu_tiles_profile(), c.spec, d);
      const Pass a = run(small_tiles, c.spec, d), b = run(one_by_one, c.spec, d);
      CHECK(norm_err(a.out, cpu.out) < 1e-5);
      CHECK(norm_err(a.grad, cpu.grad) < 1e-5);
      CHECK(norm_err(a.d_in, cpu.d_in) < 1e-5);
      if (has_groups) CHECK(norm_err(a.d_group, cpu.d_group) < 1e-5);
      CHECK(same_bits(a.out, b.out));
      CHECK(same_bits(a.grad, b.grad));
      CHECK(same_bits(a.d_in, b.d_in));
      CHECK(same_bits(a.d_group, b.d_group));
      if (!c.spec.bias)  // its non-zero bias rows are neither read nor given a gradient
        for (size_t k : bias_rows(c.spec)) CHECK(a.grad[k] == 0.0f);
    }
  }
}
