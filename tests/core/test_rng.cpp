#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "core/rng.hpp"

using namespace sgnlf;

TEST_CASE("philox matches the Random123 known-answer vectors", "[rng]") {
  // Known-answer tests from Random123's kat_vectors for philox4x32_10.
  auto r = philox4x32_10({0, 0, 0, 0}, 0, 0);
  CHECK(r == Philox4{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u});
  r = philox4x32_10({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}, 0xffffffffu, 0xffffffffu);
  CHECK(r == Philox4{0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu});
  r = philox4x32_10({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}, 0xa4093822u, 0x299f31d0u);
  CHECK(r == Philox4{0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u});
}

TEST_CASE("same seed gives the same stream, another seed or stream a different one", "[rng]") {
  Rng a(42), b(42), c(43), d(42, 1);
  bool differs_c = false, differs_d = false;
  for (int i = 0; i < 1000; ++i) {
    const auto x = a.next_u32();
    CHECK(x == b.next_u32());
    differs_c |= x != c.next_u32();
    differs_d |= x != d.next_u32();
  }
  CHECK(differs_c);
  CHECK(differs_d);
}

TEST_CASE("uniform and normal draws have the right moments", "[rng]") {
  Rng rng(1);
  const int n = 200000;
  double s = 0, s2 = 0, ns = 0, ns2 = 0, n4 = 0;
  float lo = 1, hi = 0;
  for (int i = 0; i < n; ++i) {
    const float u = rng.uniform();
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    s += u;
    s2 += double(u) * u;
    const double z = rng.normal();
    ns += z;
    ns2 += z * z;
    n4 += z * z * z * z;
  }
  CHECK(lo >= 0.0f);
  CHECK(hi < 1.0f);
  CHECK(s / n == Approx(0.5).margin(0.005));
  CHECK(s2 / n - (s / n) * (s / n) == Approx(1.0 / 12).margin(0.002));
  CHECK(ns / n == Approx(0.0).margin(0.01));
  CHECK(ns2 / n == Approx(1.0).margin(0.01));
  CHECK(n4 / n == Approx(3.0).margin(0.06));
}

TEST_CASE("below() is unbiased over a small range", "[rng]") {
  Rng rng(3);
  int counts[6] = {};
  for (int i = 0; i < 60000; ++i) ++counts[rng.below(6)];
  for (int c : counts) CHECK(c == Approx(10000).margin(400));
}
