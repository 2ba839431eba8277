// The device-vs-reference measures (support/device_tolerance.hpp): equal arrays and one-ulp
// rounding pass, a wrong element or a scaled array fails and is named (index, both values, the
// measure), values below the floor are compared absolutely, and a NaN or a size mismatch never
// passes.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "support/device_tolerance.hpp"
#include "support/test_device.hpp"

using namespace sgnlf;

namespace {
std::vector<float> reference() { return test::uniform(400, -2.0f, 2.0f, 3); }

// Every element moved by one ulp away from zero: what another device's rounding looks like.
std::vector<float> one_ulp(const std::vector<float>& v) {
  std::vector<float> r(v);
  for (auto& x : r) x = std::nextafter(x, x < 0 ? -INFINITY : INFINITY);
  return r;
}
}  // namespace

TEST_CASE("equal arrays and rounding pass", "[support][tolerance]") {
  const auto ref = reference();
  CHECK(test::sym_rel_err(ref, ref).value == 0.0);
  CHECK(test::nmse(ref, ref).value == 0.0);
  CHECK(test::sym_rel_err(ref, ref) <= 0.0);
  const auto dev = one_ulp(ref);
  CHECK(test::sym_rel_err(dev, ref) <= 1.2e-7);  // one ulp: at most 2^-23 relative
  CHECK_FALSE(test::sym_rel_err(dev, ref) <= 0.0);
  CHECK(test::nmse(dev, ref) <= 1.5e-14);
  CHECK_FALSE(test::nmse(dev, ref) <= 0.0);
  // Equal infinities are equal; so are signed zeros.
  CHECK(test::sym_rel_err({INFINITY, -INFINITY, 0.0f}, {INFINITY, -INFINITY, -0.0f}) <= 0.0);
}

TEST_CASE("a wrong element fails and is named", "[support][tolerance]") {
  const auto ref = reference();
  auto bad = one_ulp(ref);
  bad[17] = ref[17] * 1.001f;  // a wrong answer in one element, the others rounding
  const test::Discrepancy d = test::sym_rel_err(bad, ref);
  CHECK_FALSE(d <= 1e-5);
  CHECK(d <= 1.1e-3);
  CHECK(d.index == 17);
  CHECK(d.a == bad[17]);
  CHECK(d.b == ref[17]);
  CHECK(d.value == Approx(0.001 / 1.001).epsilon(1e-3));
  const std::string text = Catch::Detail::stringify(d);
  CHECK_THAT(text, Catch::Contains("symmetric relative error") && Catch::Contains("at [17] of 400") &&
                       Catch::Contains("floor 1e-06"));
  // The normalised MSE sees it too, and a whole array off by 0.1 %.
  CHECK_FALSE(test::nmse(bad, ref) <= 1e-12);
  std::vector<float> scaled(ref);
  for (auto& x : scaled) x *= 1.001f;
  const test::Discrepancy n = test::nmse(scaled, ref);
  CHECK(n.value == Approx(1e-6).epsilon(1e-2));
  CHECK_FALSE(n <= 1e-8);
  CHECK_THAT(Catch::Detail::stringify(n), Catch::Contains("normalised MSE"));
}

TEST_CASE("below the floor the error is absolute", "[support][tolerance]") {
  // 1e-9 against 0: relative error 1 (infinite without a floor), absolute 1e-9.
  CHECK(test::sym_rel_err({1e-9f}, {0.0f}, 1e-6) <= 1e-3 + 1e-9);
  CHECK_FALSE(test::sym_rel_err({1e-9f}, {0.0f}, 1e-6) <= 1e-4);
  CHECK_FALSE(test::sym_rel_err({1e-9f}, {0.0f}, 0.0) <= 0.5);
  // Above it, relative: 1 % of 10 is 1 % whatever the floor.
  CHECK(test::sym_rel_err({10.1f}, {10.0f}, 1.0).value == Approx(0.1 / 10.1).epsilon(1e-5));
}

TEST_CASE("NaN and size mismatches never pass", "[support][tolerance]") {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> ref{1.0f, 2.0f, 3.0f};
  for (const std::vector<float>& bad : {std::vector<float>{1.0f, nan, 3.0f},
                                        std::vector<float>{1.0f, INFINITY, 3.0f}}) {
    const test::Discrepancy d = test::sym_rel_err(bad, ref);
    CHECK_FALSE(d <= 1e30);
    CHECK(d.index == 1);
    CHECK_FALSE(test::nmse(bad, ref) <= 1e30);
    CHECK(test::nmse(bad, ref).index == 1);
  }
  CHECK_FALSE(test::sym_rel_err({nan}, {nan}) <= 1e30);  // a NaN in both is no agreement
  const test::Discrepancy s = test::sym_rel_err({1.0f, 2.0f}, ref);
  CHECK_FALSE(s <= 1e30);
  CHECK_THAT(s.describe(), Catch::Contains("sizes differ, 2 vs 3"));
  CHECK_FALSE(test::nmse({1.0f, 2.0f}, ref) <= 1e30);
  CHECK(test::sym_rel_err({}, {}) <= 0.0);
}
