// Comparing a device's floats with a host reference in a way that ports across OpenCL devices
// (tiny-cuda-nn's and ggml's tests do the same): a kernel's float rounding differs from device
// to device (exp, sin, sqrt and division within their OpenCL ulp bounds, contraction into FMA,
// reduction order), so a device-vs-reference check names a measure and a tolerance, and only a
// kernel that is exact by construction (integer work, copies, index maps, single IEEE
// operations, the same explicit fma order compared on the same device) is held to bit equality,
// with a comment saying why.
//
//   CHECK(test::sym_rel_err(device, reference, floor) <= tol);   // per element, worst one
//   CHECK(test::nmse(device, reference) <= tol);                 // whole array
//
// Each returns a Discrepancy, which Catch2 prints on failure: the measure, its value, the worst
// element's index and both values there, e.g. "symmetric relative error 3.1e-06 (floor 1e-06)
// at [17] of 400: 1.2345600128 vs 1.2345638275 <= 5e-07". A NaN anywhere, or arrays of
// different sizes, is an infinite discrepancy.
//
// The older helpers below (max_sym_rel_err with |a| + |b| in the denominator, max_abs_err,
// norm_err) stay for the tests written with them.
#pragma once
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <cstring>
#include <vector>

namespace sgnlf::test {

struct Discrepancy {
  std::string measure;        // "symmetric relative error (floor F)", "normalised MSE", ...
  double value = 0;           // the measure: worst element, or the whole array's
  size_t index = 0;           // the worst element (largest error or squared difference)
  double a = 0, b = 0;        // the two values there (device, reference)
  size_t size_a = 0, size_b = 0;
  std::string describe() const;
};
// The check: the measure within `tol` (a NaN or a size mismatch never is).
bool operator<=(const Discrepancy& d, double tol);

// max_i |a_i − b_i| / max(|a_i|, |b_i|, floor): per element, relative above `floor` and
// absolute (divided by floor) below it; 0 where both are equal (infinities included).
Discrepancy sym_rel_err(const std::vector<float>& a, const std::vector<float>& b,
                        double floor = 1e-6);
// Σ (a_i − b_i)² / Σ b_i² (0 when both sums are 0): for outputs whose rounding scales with the
// whole array (sums, GEMMs) rather than with each element; the index is the element with the
// largest squared difference.
Discrepancy nmse(const std::vector<float>& a, const std::vector<float>& b);

// max_i |a_i − b_i| / max(|a_i| + |b_i|, floor): symmetric relative error, the sum form.
double max_sym_rel_err(const std::vector<float>& a, const std::vector<float>& b,
                       double floor = 1e-6);
double max_abs_err(const std::vector<float>& a, const std::vector<float>& b);
// max_i |a_i − b_i| / max_i |b_i|: for float GEMM outputs, whose rounding scales with the
// magnitude of the whole output rather than of each entry.
double norm_err(const std::vector<float>& a, const std::vector<float>& b);

// Bitwise equality of two float vectors (NaN-safe, -0 != +0): only between runs on one device
// of kernels exact by construction against each other (the same explicit fma calls in the same
// order, a repeat, a copy), never against a host reference.
inline bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace sgnlf::test

namespace Catch {
template <>
struct StringMaker<sgnlf::test::Discrepancy> {
  static std::string convert(const sgnlf::test::Discrepancy& d) { return d.describe(); }
};
}  // namespace Catch
