// The radix sort's histogram scan (field::RadixScan, kernels/field/radix_scan.cl): in blocks
// (reduce-then-scan, radix_min_work_items > 0: the gpu profile's) it equals the one-work-group
// scan (entry_radix_scan, the cpu profile's) and a serial host scan word for word, on rows that
// are not multiples of a block or of a work-group, all-zero rows, one row, and words whose sums
// wrap around 2^32. The sort and the gradients built on it are checked bit for bit against the
// host's in-order sums by test_parallel_backward.cpp's [radix_tiles] cases, whose minimums of
// work-items (200, 3000) scan in 2 and 16 blocks.
#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "core/rng.hpp"
#include "field/radix_scan.hpp"
#include "support/test_device.hpp"

SGNLF_DEVICE_TESTS;
using namespace sgnlf;
using field::RadixScan;

namespace {

// Rows of `count` words: digit counts below 4096, every third row (from the second) all zero;
// with `wrap`, words of all 32 bits, so the sums wrap. One sentinel word after the rows.
std::vector<uint32_t> histogram(uint32_t units, uint32_t count, bool wrap, uint64_t seed) {
  Rng rng(seed);
  std::vector<uint32_t> h(size_t(units) * count + 1);
  for (uint32_t u = 0; u < units; ++u)
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t r = rng.next_u32();
      h[size_t(u) * count + i] = u % 3 == 1 ? 0u : wrap ? r : (r % 7 == 0 ? 0u : r >> 20);
    }
  h.back() = 0xdeadbeefu;
  return h;
}

std::vector<uint32_t> host_scan(std::vector<uint32_t> h, uint32_t units, uint32_t count) {
  for (uint32_t u = 0; u < units; ++u) {
    uint32_t acc = 0;
    for (uint32_t i = 0; i < count; ++i) {
      const uint32_t v = h[size_t(u) * count + i];
      h[size_t(u) * count + i] = acc;
      acc += v;
    }
  }
  return h;
}

std::vector<uint32_t> device_scan(RadixScan& scan, const std::vector<uint32_t>& h,
                                  uint32_t units, uint32_t count) {
  auto b = cl::Buffer::from(test::runtime(), h);
  scan.scan(b, units, count);
  return b.read_vec<uint32_t>(h.size());
}

// The blocked scan at min_work_items against the one-work-group scan and the host.
void check_scan(uint32_t units, uint32_t count, size_t min_wi, uint32_t expect_blocks) {
  INFO(units << " rows of " << count << " words, min_work_items " << min_wi);
  auto& rt = test::runtime();
  RadixScan row(rt, 0), blocked(rt, min_wi);
  CHECK(row.blocks(units, count) == 1);
  const uint32_t b = blocked.blocks(units, count);
  CHECK(b == expect_blocks);
  if (b > 1) {  // blocks of at least a work-group's words, none empty
    const uint32_t per = (count + b - 1) / b;
    CHECK(per >= RadixScan::kWorkGroup);
    CHECK(size_t(per) * (b - 1) < count);
  }
  for (bool wrap : {false, true}) {
    INFO("wrapping sums " << wrap);
    const auto h = histogram(units, count, wrap, 17 + count + wrap);
    const auto ref = host_scan(h, units, count);
    const auto one = device_scan(row, h, units, count);
    const auto blk = device_scan(blocked, h, units, count);
    CHECK(one == ref);
    CHECK(blk == ref);  // includes the sentinel: nothing past the rows written
    CHECK(blk == one);
  }
}

}  // namespace

TEST_CASE("radix histogram scan in blocks equals the one-work-group scan and the host's",
          "[field][parallel_bwd][radix_scan]") {
  // min 16 384 (the gpu profile's): ⌈16384 / (units · 64)⌉ blocks where the row has ≥ 64 words
  // a block, ⌊count / 64⌋ where it has not.
  check_scan(1, 1, 16384, 1);
  check_scan(1, 64, 16384, 1);
  check_scan(1, 65, 16384, 1);        // under two work-groups' words
  check_scan(1, 16 * 37, 16384, 9);   // 592 words: 8 blocks of 66 and one of 64
  check_scan(1, 100000, 16384, 256);
  check_scan(3, 16 * 1051, 16384, 86);
  check_scan(14, 16 * 313, 16384, 19);
  check_scan(16, 16 * 2053, 16384, 16);
  // The hash grid's big sorts (2.4e6 words over 14 levels: 16 768 work-items, 9 025 words a
  // block) and LiDAR4D's halved ones.
  check_scan(14, 16 * 10714, 16384, 19);
  check_scan(8, 16 * 2304, 16384, 32);
  // Smaller minimums, and one below a row's work-group (one block: entry_radix_scan alone).
  check_scan(3, 16 * 1050, 3000, 16);
  check_scan(3, 16 * 132, 200, 2);
  check_scan(3, 16 * 1050, 100, 1);
  check_scan(5, 4097, 100000, 64);  // ⌊4097 / 64⌋ blocks of 65 words, the last of 2
}

TEST_CASE("radix histogram scan work-items and errors", "[field][parallel_bwd][radix_scan]") {
  auto& rt = test::runtime();
  RadixScan blocked(rt, 16384);
  // The audit's rule: ≥ 1e4 work-items over the sorts' > 1e5 words.
  for (uint32_t units : {1u, 3u, 8u, 14u, 16u}) {
    INFO(units << " rows");
    const uint32_t count = uint32_t(100001 / units + 1);
    CHECK(size_t(blocked.blocks(units, count)) * units * RadixScan::kWorkGroup >= 16384);
  }
  cl::Buffer small(rt, 99 * sizeof(uint32_t));
  CHECK_THROWS_WITH(blocked.scan(small, 2, 50), Catch::Matchers::Contains("2 rows of 50 words"));
  cl::Buffer empty(rt, 4);
  CHECK_NOTHROW(blocked.scan(empty, 3, 0));
}

// For oclgrind_field_parallel: a few blocks with a short last one, an all-zero row, one row.
TEST_CASE("radix histogram scan in blocks on a small case",
          "[field][parallel_bwd][radix_scan][small]") {
  check_scan(1, 200, 500, 3);       // 67, 67, 66 words
  check_scan(3, 16 * 21, 1000, 5);  // 68 words a block, the last 64
}
