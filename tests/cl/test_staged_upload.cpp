// cl::StagedUpload (cl/staged_upload.hpp) and Buffer::write_async: non-blocking writes give the
// device the same bytes as blocking ones, in queue order, from a host copy that outlives the
// write (the caller's vector may change at once), and the launch trace counts them apart from
// the blocking transfers.
#include <catch2/catch.hpp>

#include <cstring>

#include "cl/launch_trace.hpp"
#include "cl/staged_upload.hpp"
#include "support/test_device.hpp"
#include "support/device_tolerance.hpp"

SGNLF_DEVICE_TESTS;

using namespace sgnlf;
using sgnlf::test::same_bits;

namespace {
// Bit patterns that a float conversion anywhere would change (NaN payload, denormal, -0).
std::vector<float> odd_floats(int n, uint32_t salt) {
  std::vector<float> v(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    uint32_t u = uint32_t(i) * 2654435761u ^ salt;
    if (i % 7 == 0) u = 0x7fc00001u + uint32_t(i);  // quiet NaN with a payload
    if (i % 11 == 0) u = 0x00000003u;               // denormal
    if (i % 13 == 0) u = 0x80000000u;               // -0
    std::memcpy(&v[size_t(i)], &u, 4);
  }
  return v;
}
}  // namespace

TEST_CASE("staged uploads write exactly the bytes of a blocking write", "[staged_upload]") {
  auto& rt = test::runtime();
  const int n = 3001;
  const auto v = odd_floats(n, 0x1234u);
  cl::Buffer a(rt, size_t(n) * 4), b(rt, size_t(n + 5) * 4);
  a.write_vec(v);
  cl::StagedUpload up;
  up.write_vec(b, v, 5);  // at an element offset
  // Exact by construction: both are byte copies.
  CHECK(same_bits(b.read_vec<float>(size_t(n), 5), a.read_vec<float>(size_t(n))));
  CHECK_THROWS_AS(up.write_vec(b, v, 6), Error);  // one element past the end
}

TEST_CASE("a staged upload keeps its own copy and follows the queue's order", "[staged_upload]") {
  auto& rt = test::runtime();
  const int n = 4096;
  std::vector<float> x1(static_cast<size_t>(n)), x2(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) x1[size_t(i)] = float(i), x2[size_t(i)] = float(3 * i + 1);
  cl::Buffer x(rt, size_t(n) * 4), y(rt, size_t(n) * 4);
  y.fill_zero();
  auto k = rt.kernel("common/smoke.cl", "common_saxpy_fwd");
  k.set_args(n, 1.0f, x, y);
  cl::LaunchTrace t;
  rt.set_trace(&t);
  cl::StagedUpload up;
  {
    std::vector<float> src = x1;
    up.write_vec(x, src);
    std::fill(src.begin(), src.end(), -1e30f);  // the caller's vector changes at once
  }
  k.launch({size_t(n)});  // y = x1
  up.write_vec(x, x2);    // waits for the first write only, then restages
  k.launch({size_t(n)});  // y = x1 + x2
  float* p = up.stage<float>(size_t(n));
  for (int i = 0; i < n; ++i) p[i] = 2.0f;
  up.write(x);
  k.launch({size_t(n)});  // y = x1 + x2 + 2
  rt.set_trace(nullptr);
  const auto out = y.read_vec<float>(size_t(n));
  bool ok = true;
  for (int i = 0; i < n; ++i) ok = ok && out[size_t(i)] == x1[size_t(i)] + x2[size_t(i)] + 2.0f;
  CHECK(ok);  // integers below 2^24: exact
  CHECK(t.blocking_transfers.empty());
  REQUIRE(t.async_transfers.size() == 3);
  CHECK(t.async_transfers[0].after_kernel == "(trace start)");
  CHECK(t.async_transfers[1].after_kernel == "common_saxpy_fwd");
  CHECK(t.async_transfers[2].bytes == size_t(n) * 4);
}

TEST_CASE("a staged upload waits for its write before it is destroyed or replaced",
          "[staged_upload]") {
  auto& rt = test::runtime();
  const int n = 1 << 16;
  const auto v = odd_floats(n, 0xbeefu), w = odd_floats(n, 0x5eedu);
  cl::Buffer x(rt, size_t(n) * 4);
  {
    cl::StagedUpload up;
    up.write_vec(x, v);
    CHECK(up.pending());
  }  // its copy is freed here, after the write
  CHECK(same_bits(x.read_vec<float>(size_t(n)), v));
  cl::StagedUpload a, b;
  a.write_vec(x, w);
  b.write_vec(x, v);
  a = std::move(b);  // a's pending write finished before its copy was dropped; b's moves over
  a.wait();
  CHECK_FALSE(a.pending());
  CHECK(same_bits(x.read_vec<float>(size_t(n)), v));
}
