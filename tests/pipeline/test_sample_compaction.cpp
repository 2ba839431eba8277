// Device-vs-reference tests of kernels/pipeline/sample_compaction.cl (pipeline::SampleCompaction):
// live counts of early ray termination, the device scan of the per-ray offsets, the row → ray
// map, row compaction and the expansion of the field outputs; and the launcher itself, with the
// host and the device scan; the gpu profile's ray lanes against the per-ray kernels. Bit
// equality, exact by construction on any device:
// the counts compare a running sum of additions in the kernel's order, the rest are index maps
// and copies.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "cl/launch_trace.hpp"
#include "copy_encoder.hpp"
#include "core/rng.hpp"
#include "pipeline/model/sample_compaction.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;

TEST_CASE("early ray termination kernels match the host reference",
          "[pipeline][sample-compaction][device]") {
  auto& rt = test::runtime();
  const int R = 53, S = 12, I = 6, M = S + I;
  const float eps = 1e-3f;
  Rng rng(17);
  // Coarse weights: some rays opaque early (T falls below eps at a random sample), some never.
  std::vector<float> t_c(size_t(R) * S), w_c(size_t(R) * S), t(size_t(R) * M);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 4));  // ≥ S: no surface
    float trans = 1.0f;
    for (int j = 0; j < S; ++j) {
      t_c[size_t(r) * S + j] = 0.1f + 0.2f * j + 0.05f * rng.uniform(0, 1);
      const float alpha = j == hit ? 0.99999f : (j > hit ? 0.5f : 0.01f);
      w_c[size_t(r) * S + j] = trans * alpha;
      trans *= 1.0f - alpha;
    }
    std::vector<float> tm(t_c.begin() + r * S, t_c.begin() + (r + 1) * S);
    for (int k = 0; k < I; ++k) tm.push_back(rng.uniform(0.1f, 2.6f));
    std::sort(tm.begin(), tm.end());
    std::copy(tm.begin(), tm.end(), t.begin() + r * M);
  }
  auto btc = cl::Buffer::from(rt, t_c), bwc = cl::Buffer::from(rt, w_c), bt = cl::Buffer::from(rt, t);
  cl::Buffer bcount(rt, size_t(R) * 4);
  auto live = rt.kernel("pipeline/sample_compaction.cl", "pipeline_live_count");
  live.set_args(R, S, M, eps, btc, bwc, bt, bcount).launch({cl::round_up(size_t(R), 64)}, {64}).wait();
  const auto count = bcount.read_vec<int32_t>(size_t(R));
  std::vector<int32_t> offset{0};
  int terminated = 0;
  for (int r = 0; r < R; ++r) {
    // Reference: the first coarse sample after which 1 − Σ w < eps, plus one more coarse bin.
    float acc = 0.0f;
    int expect = M;
    for (int j = 0; j + 2 < S; ++j) {
      acc += w_c[size_t(r) * S + j];
      if (1.0f - acc < eps) {
        const float t_stop = t_c[size_t(r) * S + j + 2];
        expect = 0;
        while (expect < M && t[size_t(r) * M + expect] <= t_stop) ++expect;
        break;
      }
    }
    terminated += expect < M;
    CHECK(count[size_t(r)] == expect);
    offset.push_back(offset.back() + expect);
  }
  CHECK(terminated > 10);
  CHECK(terminated < R);
  const int n = offset.back();
  auto boff = cl::Buffer::from(rt, offset);
  // Row → ray map.
  cl::Buffer bray(rt, size_t(n) * 4);
  rt.kernel("pipeline/sample_compaction.cl", "pipeline_row_ray")
      .set_args(R, boff, bray)
      .launch({cl::round_up(size_t(R), 64)}, {64})
      .wait();
  std::vector<int32_t> ray_ref;
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < count[size_t(r)]; ++k) ray_ref.push_back(r);
  CHECK(bray.read_vec<int32_t>(size_t(n)) == ray_ref);
  // Compaction of rows (width 3) and the expansion of the field outputs back.
  const int width = 3;
  std::vector<float> full(size_t(R) * M * width);
  for (auto& v : full) v = rng.uniform(-1, 1);
  auto bfull = cl::Buffer::from(rt, full);
  cl::Buffer bcomp(rt, size_t(n) * width * 4);
  const size_t global = cl::round_up(size_t(R) * M, 64);
  rt.kernel("pipeline/sample_compaction.cl", "pipeline_compact_rows")
      .set_args(R, M, width, boff, bfull, bcomp)
      .launch({global}, {64})
      .wait();
  std::vector<float> comp_ref;
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < count[size_t(r)]; ++k)
      for (int c = 0; c < width; ++c) comp_ref.push_back(full[(size_t(r) * M + k) * width + c]);
  CHECK(bcomp.read_vec<float>(comp_ref.size()) == comp_ref);
  const int stride = 16;
  std::vector<float> dens(size_t(n) * stride), head_c(size_t(n) * 2);
  for (auto& v : dens) v = rng.uniform(-3, 3);
  for (auto& v : head_c) v = rng.uniform(-3, 3);
  auto bdens = cl::Buffer::from(rt, dens), bhc = cl::Buffer::from(rt, head_c);
  auto bh0 = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M, 9.0f));
  auto bhead = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * 2, 9.0f));
  rt.kernel("pipeline/sample_compaction.cl", "pipeline_expand_outputs")
      .set_args(R, M, stride, -100.0f, boff, bdens, bhc, bh0, bhead)
      .launch({global}, {64})
      .wait();
  std::vector<float> h0_ref(size_t(R) * M, -100.0f), head_ref(size_t(R) * M * 2, 0.0f);
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < count[size_t(r)]; ++k) {
      const size_t q = size_t(r) * M + k, row = size_t(offset[size_t(r)] + k);
      h0_ref[q] = dens[row * stride];
      head_ref[2 * q] = head_c[2 * row];
      head_ref[2 * q + 1] = head_c[2 * row + 1];
    }
  CHECK(bh0.read_vec<float>(h0_ref.size()) == h0_ref);
  CHECK(bhead.read_vec<float>(head_ref.size()) == head_ref);
}

namespace {

// Coarse and merged samples of R rays (S coarse, M merged per ray; t sorted), some rays opaque
// early, and each ray's live count by the reference of pipeline_live_count.
struct Termination {
  std::vector<float> t_c, w_c, t;
  std::vector<int> count;
  std::vector<int32_t> offset{0};
};

Termination make_termination(int R, int S, int M, float eps, Rng& rng) {
  Termination d;
  d.t_c.resize(size_t(R) * S), d.w_c.resize(size_t(R) * S), d.t.resize(size_t(R) * M);
  for (int r = 0; r < R; ++r) {
    const int hit = int(rng.next_u64() % uint64_t(S + 4));  // ≥ S: no surface
    float trans = 1.0f;
    for (int j = 0; j < S; ++j) {
      d.t_c[size_t(r) * S + j] = 0.1f + 0.2f * j + 0.05f * rng.uniform(0, 1);
      const float alpha = j == hit ? 0.99999f : (j > hit ? 0.5f : 0.01f);
      d.w_c[size_t(r) * S + j] = trans * alpha;
      trans *= 1.0f - alpha;
    }
    std::vector<float> tm(d.t_c.begin() + r * S, d.t_c.begin() + (r + 1) * S);
    for (int k = S; k < M; ++k) tm.push_back(rng.uniform(0.1f, 2.6f));
    std::sort(tm.begin(), tm.end());
    std::copy(tm.begin(), tm.end(), d.t.begin() + r * M);
    float acc = 0.0f;
    int c = M;
    for (int j = 0; j + 2 < S; ++j) {
      acc += d.w_c[size_t(r) * S + j];
      if (1.0f - acc < eps) {
        const float t_stop = d.t_c[size_t(r) * S + j + 2];
        c = 0;
        while (c < M && d.t[size_t(r) * M + c] <= t_stop) ++c;
        break;
      }
    }
    d.count.push_back(c);
    d.offset.push_back(d.offset.back() + c);
  }
  return d;
}

// The live rows of `full` (R × M rows of `width` floats).
std::vector<float> live_rows(const std::vector<float>& full, const Termination& d, int M,
                             int width) {
  std::vector<float> out;
  for (size_t r = 0; r < d.count.size(); ++r)
    for (int k = 0; k < d.count[r]; ++k)
      for (int c = 0; c < width; ++c) out.push_back(full[(r * size_t(M) + k) * width + c]);
  return out;
}

}  // namespace

TEST_CASE("SampleCompaction selects, gathers and expands the live rows",
          "[pipeline][sample-compaction][device]") {
  auto& rt = test::runtime();
  const int R = 47, S = 12, M = 18, width = 5, stride = 16;
  const float eps = 1e-3f;
  Rng rng(43);
  const Termination d = make_termination(R, S, M, eps, rng);
  const int n = d.offset.back();
  REQUIRE(n < R * M);
  auto rnd = [&](size_t k, float a) {
    std::vector<float> v(k);
    for (auto& e : v) e = rng.uniform(-a, a);
    return v;
  };
  const auto x = rnd(size_t(R) * M * 3, 1), enc = rnd(size_t(R) * M * width, 1);
  pipeline::SampleCompaction live(rt, R + 3, M, S, width, eps);  // capacity above the call
  auto btc = cl::Buffer::from(rt, d.t_c), bwc = cl::Buffer::from(rt, d.w_c);
  auto bt = cl::Buffer::from(rt, d.t), bx = cl::Buffer::from(rt, x);
  auto benc = cl::Buffer::from(rt, enc);
  CHECK(live.select(R, M, btc, bwc, bt, bx) == n);
  CHECK(live.rows() == n);
  CHECK(live.counts(R) == d.count);
  CHECK(live.offsets().read_vec<int32_t>(size_t(R) + 1) == d.offset);
  CHECK(live.positions().read_vec<float>(size_t(n) * 3) == live_rows(x, d, M, 3));
  std::vector<int32_t> ray_ref;
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < d.count[size_t(r)]; ++k) ray_ref.push_back(r);
  const field::GroupIndex index = live.index(R);
  CHECK(index.n_groups == R);
  CHECK(index.offsets == &live.offsets());
  CHECK(index.point_group->read_vec<int32_t>(size_t(n)) == ray_ref);
  live.gather_encodings(R, M, benc);
  CHECK(live.encodings().read_vec<float>(size_t(n) * width) == live_rows(enc, d, M, width));

  // The field outputs back into the full layout (dead samples: σ logit −100, head 0).
  const auto dens = rnd(size_t(n) * stride, 3), head = rnd(size_t(n) * 2, 3);
  live.head_out().write_vec(head);
  auto bdens = cl::Buffer::from(rt, dens);
  auto bh0 = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M, 9.0f));
  auto bhead = cl::Buffer::from(rt, std::vector<float>(size_t(R) * M * 2, 9.0f));
  live.expand(R, M, bdens, bh0, bhead);
  std::vector<float> h0_ref(size_t(R) * M, -100.0f), head_ref(size_t(R) * M * 2, 0.0f);
  for (int r = 0; r < R; ++r)
    for (int k = 0; k < d.count[size_t(r)]; ++k) {
      const size_t q = size_t(r) * M + k, row = size_t(d.offset[size_t(r)] + k);
      h0_ref[q] = dens[row * stride];
      head_ref[2 * q] = head[2 * row];
      head_ref[2 * q + 1] = head[2 * row + 1];
    }
  CHECK(bh0.read_vec<float>(h0_ref.size()) == h0_ref);
  CHECK(bhead.read_vec<float>(head_ref.size()) == head_ref);

  // The renderer's gradients on the live rows; without g_head, grad_head() is left alone.
  const auto g_h0 = rnd(size_t(R) * M, 1), g_head = rnd(size_t(R) * M * 2, 1);
  auto bgh0 = cl::Buffer::from(rt, g_h0), bghead = cl::Buffer::from(rt, g_head);
  live.gather_gradients(R, M, bgh0, &bghead);
  CHECK(live.grad_h0().read_vec<float>(size_t(n)) == live_rows(g_h0, d, M, 1));
  CHECK(live.grad_head().read_vec<float>(size_t(n) * 2) == live_rows(g_head, d, M, 2));
  auto bgh0b = cl::Buffer::from(rt, rnd(size_t(R) * M, 1));
  live.gather_gradients(R, M, bgh0b, nullptr);
  CHECK(live.grad_head().read_vec<float>(size_t(n) * 2) == live_rows(g_head, d, M, 2));

  // encode(): the live positions through the encoder.
  test::CopyEncoder encoder;
  pipeline::SampleCompaction live3(rt, R, M, S, encoder.width(), eps);
  live3.select(R, M, btc, bwc, bt, bx);
  cl::Buffer params(rt, 4);
  live3.encode(encoder, params, 0);
  CHECK(encoder.rows == n);
  CHECK(live3.encodings().read_vec<float>(size_t(n) * 3) == live_rows(x, d, M, 3));
}

// The device profile's `compaction: device` (kernels/common/scan.clh through
// pipeline_offsets_scan): the per-ray offsets from the live counts on the device. Integer sums,
// so bit equality with the host's serial prefix sum holds on any device.
TEST_CASE("the device scan of the live counts equals the host prefix sum",
          "[pipeline][sample-compaction][scan][device]") {
  auto& rt = test::runtime();
  Rng rng(59);
  auto scan = rt.kernel("pipeline/sample_compaction.cl", "pipeline_offsets_scan");
  // Sizes around the work-group (256): fewer rays than work-items, one per work-item, chunks
  // with a tail; the audit's 4096 rays; large counts whose total nears 2^30.
  for (const auto& [n, max_count] : std::vector<std::pair<int, int>>{
           {1, 40}, {2, 40}, {63, 40}, {255, 300}, {256, 300}, {257, 300}, {1000, 300},
           {4096, 300}, {5001, 64}, {4096, 1 << 18}}) {
    CAPTURE(n, max_count);
    std::vector<int32_t> count(size_t(n) + 1), ref(size_t(n) + 1, 0);
    for (int r = 0; r < n; ++r)
      count[size_t(r)] = rng.next_u64() % 5 == 0 ? 0 : int32_t(rng.next_u64() % uint64_t(max_count + 1));
    count[size_t(n)] = 0x5eadbeef;  // whatever the slot held: the kernel writes it
    for (int r = 0; r < n; ++r) ref[size_t(r) + 1] = ref[size_t(r)] + count[size_t(r)];
    auto buf = cl::Buffer::from(rt, count);
    scan.set_args(n, buf).launch({256}, {256});
    CHECK(buf.read_vec<int32_t>(size_t(n) + 1) == ref);
  }
}

TEST_CASE("SampleCompaction gives the same offsets with the host and the device scan",
          "[pipeline][sample-compaction][scan][device]") {
  auto& rt = test::runtime();
  const int R = 301, S = 12, M = 18;
  const float eps = 1e-3f;
  Rng rng(61);
  const Termination d = make_termination(R, S, M, eps, rng);
  std::vector<float> x(size_t(R) * M * 3);
  for (auto& v : x) v = rng.uniform(-1, 1);
  auto btc = cl::Buffer::from(rt, d.t_c), bwc = cl::Buffer::from(rt, d.w_c);
  auto bt = cl::Buffer::from(rt, d.t), bx = cl::Buffer::from(rt, x);
  for (const auto mode : {cl::CompactionScan::Host, cl::CompactionScan::Device}) {
    CAPTURE(cl::compaction_name(mode));
    cl::DeviceProfile p = rt.device_profile();
    p.compaction = mode;
    std::unique_ptr<pipeline::SampleCompaction> live;
    {
      test::ProfileScope scope(p);
      live = std::make_unique<pipeline::SampleCompaction>(rt, R + 5, M, S, 3, eps);
    }
    for (int pass = 0; pass < 2; ++pass) {  // a second select over the first one's offsets
      rt.finish();
      cl::LaunchTrace trace;
      rt.set_trace(&trace);
      const long rows = live->select(R - pass, M, btc, bwc, bt, bx);
      rt.set_trace(nullptr);
      std::vector<int32_t> ref(d.offset.begin(), d.offset.end() - pass);
      CHECK(rows == ref.back());
      CHECK(live->offsets().read_vec<int32_t>(ref.size()) == ref);
      const std::vector<float> x_live = live_rows(x, d, M, 3);  // rays 0..R-1; a prefix for fewer
      CHECK(live->positions().read_vec<float>(size_t(rows) * 3) ==
            std::vector<float>(x_live.begin(), x_live.begin() + rows * 3));
      // Host: the counts read and the offsets written; device: the total read, 4 bytes.
      if (mode == cl::CompactionScan::Host) {
        REQUIRE(trace.blocking_transfers.size() == 2);
        CHECK(trace.blocking_transfers[0].bytes == size_t(R - pass) * 4);
      } else {
        REQUIRE(trace.blocking_transfers.size() == 1);
        CHECK(trace.blocking_transfers[0].read);
        CHECK(trace.blocking_transfers[0].bytes == 4);
      }
    }
  }
}

// The gpu profile's ray_work_items lanes per ray (pipeline_live_count_wide, whose lanes split
// the merged samples and take the least first dead sample; pipeline_row_ray_wide): integers, so
// the offsets and each live row's ray equal the per-ray kernels' (the cpu profile's) and the
// host reference bit for bit on any device, at lane counts 2, 32 (the gpu profile's) and 64 (a
// whole work-group per ray), ray counts that leave a work-group part empty, M below and above
// the lanes, and merged samples out of order (the walk stops at the first one past t_stop).
namespace {
void check_ray_lanes(const std::vector<int>& Ms, const std::vector<int>& Rs,
                     const std::vector<int>& lane_counts) {
  auto& rt = test::runtime();
  const int S = 12;
  const float eps = 1e-3f;
  for (const int M : Ms) {
    for (const int R : Rs) {
      Rng rng(uint64_t(67 + M + R));
      Termination d = make_termination(R, S, M, eps, rng);
      // Every 4th ray's merged samples reversed in their second half: not sorted any more.
      for (int r = 0; r < R; r += 4)
        std::reverse(d.t.begin() + size_t(r) * M + M / 2, d.t.begin() + size_t(r + 1) * M);
      std::vector<float> x(size_t(R) * M * 3);
      for (auto& v : x) v = rng.uniform(-1, 1);
      auto btc = cl::Buffer::from(rt, d.t_c), bwc = cl::Buffer::from(rt, d.w_c);
      auto bt = cl::Buffer::from(rt, d.t), bx = cl::Buffer::from(rt, x);
      auto run = [&](const cl::DeviceProfile& p) {
        test::ProfileScope scope(p);
        pipeline::SampleCompaction live(rt, R, M, S, 3, eps);
        const long rows = live.select(R, M, btc, bwc, bt, bx);
        return std::make_pair(live.offsets().read_vec<int32_t>(size_t(R) + 1),
                              live.index(R).point_group->read_vec<int32_t>(size_t(rows)));
      };
      const auto cpu = run(cl::cpu_profile());
      // The cpu kernels against the host reference: each row's ray from their offsets, and the
      // counts of the rays left sorted (the others' are d.count's no more).
      std::vector<int32_t> ray_ref;
      for (int r = 0; r < R; ++r)
        for (int k = cpu.first[size_t(r)]; k < cpu.first[size_t(r) + 1]; ++k) ray_ref.push_back(r);
      CHECK(cpu.second == ray_ref);
      for (int r = 1; r < R; r += 4)
        CHECK(cpu.first[size_t(r) + 1] - cpu.first[size_t(r)] == d.count[size_t(r)]);
      for (const int lanes : lane_counts) {
        CAPTURE(M, R, lanes);
        cl::DeviceProfile p = cl::gpu_profile();
        p.ray_work_items = lanes;
        CHECK(run(p) == cpu);
      }
    }
  }
}
}  // namespace

TEST_CASE("SampleCompaction's per-ray lanes give the per-ray kernels' offsets and rows",
          "[pipeline][sample-compaction][ray_lanes][device]") {
  check_ray_lanes({18, 75}, {1, 3, 301}, {2, 32, 64});
}

// The same at the gpu profile's 32 lanes on a few rays (oclgrind_pipeline).
TEST_CASE("SampleCompaction's per-ray lanes on a small case",
          "[pipeline][sample-compaction][ray_lanes][small][device]") {
  check_ray_lanes({40}, {3}, {32});
}
