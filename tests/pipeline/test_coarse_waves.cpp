// Device-vs-reference tests of kernels/pipeline/coarse_waves.cl (pipeline::CoarseWaves): the
// per-ray done flags, the wave gather and scatter, and the fill; and the launcher itself. Bit
// equality throughout, exact by construction on any device: the done flags compare a running
// sum of additions in the kernel's order, the rest are index maps and copies.
#include <catch2/catch.hpp>

#include <vector>

#include "core/rng.hpp"
#include "pipeline/model/coarse_waves.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("coarse wave kernels match the host reference",
          "[pipeline][coarse-waves][device]") {
  auto& rt = test::runtime();
  const int R = 41, S = 16, lf = 5, stride = 16;
  const float eps = 1e-3f;
  Rng rng(23);
  // Coarse weights of rays that become opaque at a random sample (≥ S: never).
  std::vector<float> w_c(size_t(R) * S);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 3));
    float trans = 1.0f;
    for (int j = 0; j < S; ++j) {
      const float alpha = j == hit ? 0.99999f : (j > hit ? 0.5f : 0.02f);
      w_c[size_t(r) * S + j] = trans * alpha;
      trans *= 1.0f - alpha;
    }
  }
  auto bwc = cl::Buffer::from(rt, w_c);
  cl::Buffer bdone(rt, size_t(R) * 4);
  auto done_k = rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_done");
  int n_done_mid = 0, n_done_end = 0;
  for (int end : {4, 8, 12, 16}) {
    done_k.set_args(R, S, end, eps, bwc, bdone).launch({cl::round_up(size_t(R), 64)}, {64}).wait();
    const auto done = bdone.read_vec<int32_t>(size_t(R));
    for (int r = 0; r < R; ++r) {
      // Reference: the termination index j + 2 of pipeline_live_count lies below `end`.
      float acc = 0.0f;
      int stop = -1;
      for (int j = 0; j + 2 < S; ++j) {
        acc += w_c[size_t(r) * S + j];
        if (1.0f - acc < eps) {
          stop = j + 2;
          break;
        }
      }
      const int expect = stop >= 0 && stop < end ? 1 : 0;
      CHECK(done[size_t(r)] == expect);
      if (end == 8) n_done_mid += expect;
      if (end == 16) n_done_end += expect;
    }
  }
  CHECK(n_done_mid > 3);        // some rays stop in the first half
  CHECK(n_done_end > n_done_mid);  // more by the end
  CHECK(n_done_end < R);        // and some never

  // Gather of one wave's rows of the alive rays, and the scatter of its outputs back.
  const int s0 = 5, width = 6;
  std::vector<int32_t> alive;
  for (int r = 0; r < R; ++r)
    if (rng.uniform(0, 1) < 0.6f) alive.push_back(r);
  const int n_alive = int(alive.size()), rows = n_alive * width;
  std::vector<float> x_c(size_t(R) * S * 3), enc_w(size_t(rows) * lf), dens_w(size_t(rows) * stride);
  for (auto& v : x_c) v = rng.uniform(-1, 1);
  for (auto& v : enc_w) v = rng.uniform(-1, 1);
  for (auto& v : dens_w) v = rng.uniform(-3, 3);
  auto balive = cl::Buffer::from(rt, alive), bxc = cl::Buffer::from(rt, x_c);
  cl::Buffer bxw(rt, size_t(rows) * 3 * 4);
  const size_t global = cl::round_up(size_t(rows), 64);
  rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_gather")
      .set_args(n_alive, S, s0, width, balive, bxc, bxw)
      .launch({global}, {64})
      .wait();
  std::vector<float> xw_ref;
  for (int a = 0; a < n_alive; ++a)
    for (int i = 0; i < width; ++i)
      for (int c = 0; c < 3; ++c) xw_ref.push_back(x_c[(size_t(alive[size_t(a)]) * S + s0 + i) * 3 + c]);
  CHECK(bxw.read_vec<float>(xw_ref.size()) == xw_ref);
  std::vector<float> enc_ref(size_t(R) * S * lf, 7.0f), h0_ref(size_t(R) * S, -100.0f);
  auto bencw = cl::Buffer::from(rt, enc_w), bdensw = cl::Buffer::from(rt, dens_w);
  auto benc = cl::Buffer::from(rt, enc_ref), bh0 = cl::Buffer::from(rt, h0_ref);
  rt.kernel("pipeline/coarse_waves.cl", "pipeline_wave_scatter")
      .set_args(n_alive, S, s0, width, lf, stride, balive, bencw, bdensw, benc, bh0)
      .launch({global}, {64})
      .wait();
  for (int a = 0; a < n_alive; ++a)
    for (int i = 0; i < width; ++i) {
      const size_t q = size_t(a) * width + i, dst = size_t(alive[size_t(a)]) * S + s0 + i;
      for (int k = 0; k < lf; ++k) enc_ref[dst * lf + k] = enc_w[q * lf + k];
      h0_ref[dst] = dens_w[q * stride];
    }
  CHECK(benc.read_vec<float>(enc_ref.size()) == enc_ref);
  CHECK(bh0.read_vec<float>(h0_ref.size()) == h0_ref);
  // pipeline_fill.
  cl::Buffer bf(rt, 70 * 4);
  rt.kernel("pipeline/coarse_waves.cl", "pipeline_fill").set_args(70, -3.5f, bf).launch({128}, {64}).wait();
  CHECK(bf.read_vec<float>(70) == std::vector<float>(70, -3.5f));
}

TEST_CASE("CoarseWaves evaluates each wave on the rays not stopped yet",
          "[pipeline][coarse-waves][device]") {
  auto& rt = test::runtime();
  const int R = 31, S = 12, waves = 3, lf = 4, stride = 16;
  const float eps = 1e-3f;
  Rng rng(47);
  // Coarse sample (r, s) sits at (r, s, 0.5); a fake field gives it σ "logit" alpha[r][s] and
  // the encoding (r, s, r + s, 1); a fake renderer's weights are w = T·α, α = 0 for dead samples.
  std::vector<float> x_c(size_t(R) * S * 3), alpha(size_t(R) * S);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 3));  // ≥ S: never opaque
    for (int s = 0; s < S; ++s) {
      const size_t q = size_t(r) * S + s;
      x_c[3 * q] = float(r), x_c[3 * q + 1] = float(s), x_c[3 * q + 2] = 0.5f;
      alpha[q] = s == hit ? 0.99999f : (s > hit ? 0.5f : 0.02f);
    }
  }
  auto weights_of = [&](const std::vector<float>& h0) {
    std::vector<float> w(h0.size());
    for (int r = 0; r < R; ++r) {
      float trans = 1.0f;
      for (int s = 0; s < S; ++s) {
        const size_t q = size_t(r) * S + s;
        const float a = h0[q] == -100.0f ? 0.0f : h0[q];
        w[q] = trans * a;
        trans *= 1.0f - a;
      }
    }
    return w;
  };
  auto bxc = cl::Buffer::from(rt, x_c);
  cl::Buffer bwc(rt, size_t(R) * S * 4), bh0(rt, size_t(R) * S * 4);
  cl::Buffer bdens(rt, size_t(R) * S * stride * 4);
  auto benc = cl::Buffer::from(rt, std::vector<float>(size_t(R) * S * lf, 7.0f));
  std::vector<int> field_rows;
  int weight_calls = 0;
  const pipeline::CoarseWaves::Field field = [&](const cl::Buffer& x, int rows,
                                                 cl::Buffer& enc) -> const cl::Buffer& {
    const auto p = x.read_vec<float>(size_t(rows) * 3);
    std::vector<float> e(size_t(rows) * lf), dn(size_t(rows) * stride, 0.0f);
    for (int k = 0; k < rows; ++k) {
      const float r = p[3 * size_t(k)], s = p[3 * size_t(k) + 1];
      e[size_t(k) * lf] = r, e[size_t(k) * lf + 1] = s, e[size_t(k) * lf + 2] = r + s;
      e[size_t(k) * lf + 3] = 1.0f;
      dn[size_t(k) * stride] = alpha[size_t(r) * S + size_t(s)];
    }
    enc.write_vec(e);
    bdens.write_vec(dn);
    field_rows.push_back(rows);
    return bdens;
  };
  const auto weights = [&] {
    bwc.write_vec(weights_of(bh0.read_vec<float>(size_t(R) * S)));
    ++weight_calls;
  };
  pipeline::CoarseWaves cw(rt, R + 2, S, waves, lf, eps);  // capacity above the call
  const long evaluated = cw.run(R, bxc, bwc, benc, bh0, field, weights);

  // Reference: ray r runs wave k while its termination index over the complete pass (as
  // pipeline_live_count finds it) does not lie below the end of wave k − 1.
  const auto w_full = weights_of(alpha);
  std::vector<float> h0_ref(size_t(R) * S, -100.0f), enc_ref(size_t(R) * S * lf, 7.0f);
  std::vector<int> rows_ref(waves, 0);
  long evaluated_ref = 0;
  int stopped_early = 0;
  for (int r = 0; r < R; ++r) {
    float acc = 0.0f;
    int stop = -1;
    for (int j = 0; j + 2 < S; ++j) {
      acc += w_full[size_t(r) * S + j];
      if (1.0f - acc < eps) {
        stop = j + 2;
        break;
      }
    }
    for (int k = 0; k < waves; ++k) {
      const int s0 = S * k / waves, s1 = S * (k + 1) / waves;
      if (k > 0 && stop >= 0 && stop < S * k / waves) break;
      rows_ref[size_t(k)] += s1 - s0;
      evaluated_ref += s1 - s0;
      for (int s = s0; s < s1; ++s) {
        const size_t q = size_t(r) * S + s;
        h0_ref[q] = alpha[q];
        const float e[4] = {float(r), float(s), float(r + s), 1.0f};
        for (int c = 0; c < lf; ++c) enc_ref[q * lf + c] = e[c];
      }
    }
    stopped_early += stop >= 0 && stop < S * (waves - 1) / waves;
  }
  CHECK(stopped_early > 3);
  CHECK(stopped_early < R);
  CHECK(evaluated == evaluated_ref);
  CHECK(field_rows == rows_ref);
  CHECK(weight_calls == waves);
  CHECK(bh0.read_vec<float>(h0_ref.size()) == h0_ref);
  CHECK(benc.read_vec<float>(enc_ref.size()) == enc_ref);
}
