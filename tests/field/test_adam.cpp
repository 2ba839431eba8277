// Adam over a flat buffer: device vs host reference over several steps and parameter groups.
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "field/adam.hpp"
#include "reference.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("Adam matches the host reference per group", "[field][adam]") {
  auto& rt = test::runtime();
  const size_t n = 5000;
  field::AdamConfig cfg;
  cfg.weight_decay = 1e-3f;
  field::Adam adam(rt, n, cfg);
  Rng rng(9);
  std::vector<float> p(n), m(n, 0.0f), v(n, 0.0f);
  for (auto& x : p) x = rng.uniform(-1.0f, 1.0f);
  auto b_p = cl::Buffer::from(rt, p);
  cl::Buffer b_g(rt, n * 4);
  CHECK_THROWS_AS(adam.update(b_p, b_g, 0, n, 1e-2f), Error);  // no begin_step()
  for (int step = 1; step <= 5; ++step) {
    std::vector<float> g(n);
    for (auto& x : g) x = rng.uniform(-1.0f, 1.0f) * (step == 3 ? 0.0f : 1.0f);
    b_g.write_vec(g);
    adam.begin_step();
    adam.update(b_p, b_g, 0, 3000, 1e-2f);
    adam.update(b_p, b_g, 3000, 1500, 1e-3f);
    adam.update(b_p, b_g, 4500, 500, 0.0f);  // frozen group: moments move, params stay
    test::ref::adam_step(p, g, m, v, 0, 3000, 1e-2f, step, cfg.beta1, cfg.beta2, cfg.eps,
                         cfg.weight_decay);
    test::ref::adam_step(p, g, m, v, 3000, 1500, 1e-3f, step, cfg.beta1, cfg.beta2, cfg.eps,
                         cfg.weight_decay);
    test::ref::adam_step(p, g, m, v, 4500, 500, 0.0f, step, cfg.beta1, cfg.beta2, cfg.eps,
                         cfg.weight_decay);
  }
  CHECK(adam.step() == 5);
  CHECK(test::max_abs_err(b_p.read_vec<float>(n), p) < 1e-6);
  // Moments are O(|g|) ≤ 1: float rounding ~1e-7 absolute per step.
  CHECK(test::max_abs_err(adam.m().read_vec<float>(n), m) < 1e-6);
  CHECK(test::max_abs_err(adam.v().read_vec<float>(n), v) < 1e-6);
  field::AdamConfig bad;
  bad.beta2 = 1.5f;
  CHECK_THROWS_AS(bad.validate(), ConfigError);
}
