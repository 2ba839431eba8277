// Device-vs-reference tests of kernels/pipeline/encoding_reuse.cl (pipeline::EncodingReuse):
// the importance samples' positions, and the merged positions and encodings in sample order;
// and the launcher itself. Bit equality: index maps and copies, exact by construction.
#include <catch2/catch.hpp>

#include <utility>

#include "copy_encoder.hpp"
#include "core/rng.hpp"
#include "pipeline/model/encoding_reuse.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("pipeline_fine_points and pipeline_merge_encodings match the host reference",
          "[pipeline][encoding-reuse][device]") {
  auto& rt = test::runtime();
  const int R = 37, S = 11, I = 5, M = S + I, width = 6;
  Rng rng(7);
  // Each ray's merged order is a random permutation of its S + I sources.
  std::vector<int> src(size_t(R) * M);
  for (int r = 0; r < R; ++r) {
    int* p = &src[size_t(r) * M];
    for (int k = 0; k < M; ++k) p[k] = k;
    for (int k = M - 1; k > 0; --k) std::swap(p[k], p[int(rng.next_u64() % uint64_t(k + 1))]);
  }
  auto rnd = [&](size_t n) {
    std::vector<float> v(n);
    for (auto& e : v) e = rng.uniform(-1, 1);
    return v;
  };
  const auto x = rnd(size_t(R) * M * 3), x_c = rnd(size_t(R) * S * 3);
  const auto enc_c = rnd(size_t(R) * S * width), enc_f = rnd(size_t(R) * I * width);
  auto bsrc = cl::Buffer::from(rt, src), bx = cl::Buffer::from(rt, x);
  auto bxc = cl::Buffer::from(rt, x_c), bec = cl::Buffer::from(rt, enc_c);
  auto bef = cl::Buffer::from(rt, enc_f);
  cl::Buffer bxf(rt, size_t(R) * I * 12), benc(rt, size_t(R) * M * width * 4);
  const size_t global = cl::round_up(size_t(R) * M, 64);
  auto pick = rt.kernel("pipeline/encoding_reuse.cl", "pipeline_fine_points");
  pick.set_args(R, S, M, bsrc, bx, bxf).launch({global}, {64}).wait();
  auto merge = rt.kernel("pipeline/encoding_reuse.cl", "pipeline_merge_encodings");
  merge.set_args(R, S, M, width, bsrc, bxc, bec, bef, bx, benc).launch({global}, {64}).wait();

  std::vector<float> xf_ref(size_t(R) * I * 3), x_ref = x, enc_ref(size_t(R) * M * width);
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < M; ++k) {
      const size_t q = size_t(r) * M + k;
      const int s = src[q];
      for (int c = 0; c < 3; ++c) {
        if (s >= S) xf_ref[(size_t(r) * I + (s - S)) * 3 + c] = x[3 * q + c];
        else x_ref[3 * q + c] = x_c[(size_t(r) * S + s) * 3 + c];
      }
      for (int c = 0; c < width; ++c)
        enc_ref[q * width + c] = s < S ? enc_c[(size_t(r) * S + s) * width + c]
                                       : enc_f[(size_t(r) * I + (s - S)) * width + c];
    }
  CHECK(bxf.read_vec<float>(xf_ref.size()) == xf_ref);
  CHECK(bx.read_vec<float>(x_ref.size()) == x_ref);
  CHECK(benc.read_vec<float>(enc_ref.size()) == enc_ref);
}

TEST_CASE("EncodingReuse encodes the importance samples only and merges in sample order",
          "[pipeline][encoding-reuse][device]") {
  auto& rt = test::runtime();
  const int R = 23, S = 9, I = 7, M = S + I;
  Rng rng(41);
  std::vector<int> src(size_t(R) * M);
  for (int r = 0; r < R; ++r) {
    int* p = &src[size_t(r) * M];
    for (int k = 0; k < M; ++k) p[k] = k;
    for (int k = M - 1; k > 0; --k) std::swap(p[k], p[int(rng.next_u64() % uint64_t(k + 1))]);
  }
  auto rnd = [&](size_t n) {
    std::vector<float> v(n);
    for (auto& e : v) e = rng.uniform(-1, 1);
    return v;
  };
  // Encodings of width 3 (test::CopyEncoder: a point's encoding is its position).
  const auto x = rnd(size_t(R) * M * 3), x_c = rnd(size_t(R) * S * 3);
  const auto enc_c = rnd(size_t(R) * S * 3);
  test::CopyEncoder encoder;
  pipeline::EncodingReuse reuse(rt, R + 5, S, I, encoder.width());  // capacity above the call
  reuse.sources().write_vec(src);
  auto bx = cl::Buffer::from(rt, x), bxc = cl::Buffer::from(rt, x_c);
  auto bec = cl::Buffer::from(rt, enc_c);
  cl::Buffer benc(rt, size_t(R) * M * 3 * 4), params(rt, 4);
  reuse.encode_importance(R, bx, encoder, params, 0);
  reuse.merge(R, bxc, bec, bx, benc);
  CHECK(encoder.calls == 1);
  CHECK(encoder.rows == long(R) * I);
  std::vector<float> x_ref = x, enc_ref(size_t(R) * M * 3);
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < M; ++k) {
      const size_t q = size_t(r) * M + k;
      const int s = src[q];
      for (int c = 0; c < 3; ++c) {
        if (s < S) {
          x_ref[3 * q + c] = x_c[(size_t(r) * S + s) * 3 + c];
          enc_ref[3 * q + c] = enc_c[(size_t(r) * S + s) * 3 + c];
        } else {
          enc_ref[3 * q + c] = x[3 * q + c];  // its own position, encoded
        }
      }
    }
  CHECK(bx.read_vec<float>(x_ref.size()) == x_ref);
  CHECK(benc.read_vec<float>(enc_ref.size()) == enc_ref);
}
