// Philox4x32-10 counter-based generator (Salmon et al., SC'11). The same function is in
// kernels/common/philox.clh, so host and device draw identical integer streams from
// (seed, stream, index). std::*_distribution is never used: it differs between libraries.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>

namespace sgnlf {

using Philox4 = std::array<uint32_t, 4>;

inline Philox4 philox4x32_10(Philox4 ctr, uint32_t k0, uint32_t k1) {
  constexpr uint32_t M0 = 0xD2511F53u, M1 = 0xCD9E8D57u;
  constexpr uint32_t W0 = 0x9E3779B9u, W1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    const uint64_t p0 = uint64_t(M0) * ctr[0];
    const uint64_t p1 = uint64_t(M1) * ctr[2];
    const uint32_t hi0 = uint32_t(p0 >> 32), lo0 = uint32_t(p0);
    const uint32_t hi1 = uint32_t(p1 >> 32), lo1 = uint32_t(p1);
    ctr = {hi1 ^ ctr[1] ^ k0, lo1, hi0 ^ ctr[3] ^ k1, lo0};
    k0 += W0;
    k1 += W1;
  }
  return ctr;
}

// Four 32-bit words for block `index` of stream `stream` under `seed`.
inline Philox4 philox_block(uint64_t seed, uint32_t stream, uint64_t index) {
  return philox4x32_10({uint32_t(index), uint32_t(index >> 32), stream, 0u}, uint32_t(seed),
                       uint32_t(seed >> 32));
}

// Uniform in [0, 1) with 24 random bits: exact in float, identical on host and device.
inline float u32_to_unit_float(uint32_t x) { return float(x >> 8) * (1.0f / 16777216.0f); }

// Sequential generator over one stream, four words per block.
// Same seed, same draws whatever the compiler only if each call is sequenced: never draw twice
// within one function call's arguments (f(rng.uniform(), rng.uniform()), Vec3(rng.normal(),
// ...)), whose evaluation order is unspecified (GCC goes last to first, Clang first to last; a
// Clang build once simulated another street from the same seed). Draw into named values first.
class Rng {
 public:
  Rng(uint64_t seed, uint32_t stream = 0) : seed_(seed), stream_(stream) {}

  uint32_t next_u32() {
    if (lane_ == 4) {
      block_ = philox_block(seed_, stream_, index_++);
      lane_ = 0;
    }
    return block_[lane_++];
  }
  uint64_t next_u64() {
    const uint64_t lo = next_u32();
    return (uint64_t(next_u32()) << 32) | lo;
  }
  float uniform() { return u32_to_unit_float(next_u32()); }
  double uniform_double() { return double(next_u64() >> 11) * (1.0 / 9007199254740992.0); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
  // Unbiased integer in [0, n) by rejection (Lemire's method is avoided for portability).
  uint32_t below(uint32_t n) {
    const uint32_t limit = uint32_t(0xFFFFFFFFu - (0xFFFFFFFFu % n + 1u) % n);
    uint32_t x;
    do x = next_u32();
    while (x > limit);
    return x % n;
  }
  // Standard normal by Box-Muller in double precision.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (double(next_u32()) + 0.5) * (1.0 / 4294967296.0);
    const double u2 = (double(next_u32()) + 0.5) * (1.0 / 4294967296.0);
    const double r = std::sqrt(-2.0 * std::log(u1));
    const double a = 6.283185307179586 * u2;
    spare_ = r * std::sin(a);
    has_spare_ = true;
    return r * std::cos(a);
  }

 private:
  uint64_t seed_;
  uint32_t stream_;
  uint64_t index_ = 0;
  Philox4 block_{};
  int lane_ = 4;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace sgnlf
