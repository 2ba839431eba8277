// Determinism: the same seed on the same device gives bit-identical parameters (and ray-origin
// and direction gradients) after a few training steps of the whole field: hash grid → density
// MLP → head input with the direction encoding → LiDAR head, Adam over one flat buffer.
#include <catch2/catch.hpp>

#include <cstring>

#include "core/rng.hpp"
#include "field/adam.hpp"
#include "field/dir_encoding.hpp"
#include "field/hash_grid.hpp"
#include "field/mlp.hpp"
#include "field/param_layout.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using field::Activation;

namespace {
struct TrainResult {
  std::vector<float> params, d_x, d_dir;
  double first_loss = 0, last_loss = 0;
};

TrainResult train(uint64_t seed, int steps, bool deterministic) {
  auto& rt = test::runtime();
  field::HashGridConfig hc;
  hc.levels = 8;
  hc.log2_table_size = 14;
  hc.per_level_scale = 1.5f;
  hc.deterministic = deterministic;
  field::HashGrid grid(rt, hc);
  field::Mlp density(rt, field::make_mlp_spec(grid.n_output(), 64, 1, 16, Activation::Relu));
  field::DirEncoding dir_enc(rt);
  field::Mlp head(rt, field::make_mlp_spec(dir_enc.head_width(), 64, 3, 2, Activation::Relu));
  field::ParamLayout layout;
  const auto s_grid = layout.add("hash_grid", grid.n_params());
  const auto s_dens = layout.add("density_mlp", density.n_params());
  const auto s_head = layout.add("head_mlp", head.n_params());
  std::vector<float> host(layout.total(), 0.0f);
  grid.init_params(host, s_grid.offset, seed);
  density.init_params(host, s_dens.offset, seed + 1);
  head.init_params(host, s_head.offset, seed + 2);

  const int rays = 128, samples = 32, n = rays * samples;
  Rng rng(seed + 3);
  std::vector<float> x(size_t(n) * 3), dir(size_t(rays) * 3), target(size_t(n) * 3);
  for (auto& v : x) v = rng.uniform(-1.0f, 1.0f);
  for (auto& v : dir) v = rng.uniform(-0.6f, 0.6f);
  for (auto& v : target) v = rng.uniform(0.0f, 1.0f);

  auto b_params = cl::Buffer::from(rt, host);
  cl::Buffer b_grad(rt, host.size() * 4);
  b_grad.fill_zero();
  auto b_x = cl::Buffer::from(rt, x), b_dir = cl::Buffer::from(rt, dir);
  cl::Buffer b_enc(rt, size_t(n) * grid.n_output() * 4), b_dens(rt, size_t(n) * 64),
      b_denc(rt, size_t(rays) * 72 * 4), b_head_in(rt, size_t(n) * 87 * 4),
      b_out(rt, size_t(n) * 8), b_dout(rt, size_t(n) * 8), b_dhead_in(rt, size_t(n) * 87 * 4),
      b_ddens(rt, size_t(n) * 64), b_dpenc(rt, size_t(n) * grid.n_output() * 4),
      b_ddenc(rt, size_t(rays) * 72 * 4), b_dx(rt, size_t(n) * 12), b_ddir(rt, size_t(rays) * 12);
  field::MlpContext c_dens, c_head;
  field::Adam adam(rt, layout.total());
  TrainResult res;
  for (int step = 0; step < steps; ++step) {
    grid.forward(b_params, s_grid.offset, b_x, n, b_enc);
    density.forward(b_params, s_dens.offset, b_enc, n, b_dens, c_dens);
    dir_enc.forward(b_dir, rays, b_denc);
    dir_enc.head_input_forward(b_dens, b_denc, rays, samples, b_head_in);
    head.forward(b_params, s_head.offset, b_head_in, n, b_out, c_head);
    // Loss 0.5 Σ (out − t)² + 0.5 Σ (dens0 − t)² on the host (the renderer's job elsewhere).
    const auto out = b_out.read_vec<float>(size_t(n) * 2);
    auto dens = b_dens.read_vec<float>(size_t(n) * 16);
    std::vector<float> d_out(out.size()), d_dens(dens.size(), 0.0f);
    double loss = 0;
    for (int i = 0; i < n; ++i) {
      for (int k = 0; k < 2; ++k) {
        d_out[size_t(i) * 2 + k] = (out[size_t(i) * 2 + k] - target[size_t(i) * 3 + k]) / n;
        loss += 0.5 * d_out[size_t(i) * 2 + k] * d_out[size_t(i) * 2 + k] * n * n;
      }
      d_dens[size_t(i) * 16] = (dens[size_t(i) * 16] - target[size_t(i) * 3 + 2]) / n;
    }
    if (step == 0) res.first_loss = loss;
    res.last_loss = loss;
    b_dout.write_vec(d_out);
    b_ddens.write_vec(d_dens);
    head.backward(b_params, s_head.offset, c_head, b_out, b_dout, b_grad, s_head.offset,
                  &b_dhead_in);
    dir_enc.head_input_backward(b_dhead_in, rays, samples, b_ddens, b_ddenc);
    dir_enc.backward(b_dir, rays, b_ddenc, b_ddir);
    density.backward(b_params, s_dens.offset, c_dens, b_dens, b_ddens, b_grad, s_dens.offset,
                     &b_dpenc);
    grid.backward(b_params, s_grid.offset, b_x, n, b_dpenc, b_grad, s_grid.offset, &b_dx);
    adam.begin_step();
    adam.update(b_params, b_grad, s_grid.offset, s_grid.count, 1e-2f);
    adam.update(b_params, b_grad, s_dens.offset, s_dens.count + s_head.count +
                (s_head.offset - s_dens.offset - s_dens.count), 1e-3f);
    rt.finish();
  }
  res.params = b_params.read_vec<float>(host.size());
  res.d_x = b_dx.read_vec<float>(size_t(n) * 3);
  res.d_dir = b_ddir.read_vec<float>(size_t(rays) * 3);
  return res;
}

bool bit_identical(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
}  // namespace

TEST_CASE("training steps from one seed are bit-identical", "[field][determinism]") {
  const auto a = train(42, 6, true);
  const auto b = train(42, 6, true);
  CHECK(a.last_loss < a.first_loss);  // the steps do train
  CHECK(bit_identical(a.params, b.params));
  CHECK(bit_identical(a.d_x, b.d_x));
  CHECK(bit_identical(a.d_dir, b.d_dir));
  const auto c = train(43, 6, true);
  CHECK_FALSE(bit_identical(a.params, c.params));  // the comparison can fail
}
