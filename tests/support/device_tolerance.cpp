#include "support/device_tolerance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace sgnlf::test {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double v, const char* f = "%.10g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

Discrepancy start(std::string measure, const std::vector<float>& a, const std::vector<float>& b) {
  Discrepancy d;
  d.measure = std::move(measure);
  d.size_a = a.size();
  d.size_b = b.size();
  if (a.size() != b.size()) d.value = kInf;
  return d;
}

// v > 0: the elements differ (a non-finite difference is kInf).
void worst(Discrepancy& d, double v, size_t i, float a, float b) {
  if (v > d.value) {
    d.value = v;
    d.index = i;
    d.a = a;
    d.b = b;
  }
}

}  // namespace

std::string Discrepancy::describe() const {
  if (size_a != size_b)
    return measure + ": sizes differ, " + std::to_string(size_a) + " vs " + std::to_string(size_b);
  if (size_a == 0) return measure + " 0 (empty arrays)";
  return measure + " " + num(value, "%.3g") + " at [" + std::to_string(index) + "] of " +
         std::to_string(size_a) + ": " + num(a) + " vs " + num(b);
}

bool operator<=(const Discrepancy& d, double tol) {
  return d.size_a == d.size_b && !std::isnan(d.value) && d.value <= tol;
}

Discrepancy sym_rel_err(const std::vector<float>& a, const std::vector<float>& b, double floor) {
  Discrepancy d = start("symmetric relative error (floor " + num(floor, "%g") + ")", a, b);
  if (d.size_a != d.size_b) return d;
  for (size_t i = 0; i < a.size(); ++i) {
    const double x = a[i], y = b[i];
    if (x == y) continue;  // equal, infinities included
    const double s = std::max({std::fabs(x), std::fabs(y), floor});
    const double e = std::isfinite(x) && std::isfinite(y) ? std::fabs(x - y) / s : kInf;
    worst(d, e, i, a[i], b[i]);
  }
  return d;
}

Discrepancy nmse(const std::vector<float>& a, const std::vector<float>& b) {
  Discrepancy d = start("normalised MSE", a, b);
  if (d.size_a != d.size_b) return d;
  double num2 = 0, den = 0, largest = -1;
  for (size_t i = 0; i < a.size(); ++i) {
    const double x = a[i], y = b[i];
    const double q = x == y ? 0.0 : (std::isfinite(x) && std::isfinite(y) ? (x - y) * (x - y) : kInf);
    num2 += q;
    den += y * y;
    if (q > largest) {
      largest = q;
      d.index = i;
      d.a = a[i];
      d.b = b[i];
    }
  }
  d.value = num2 == 0 ? 0.0 : (std::isfinite(num2) && den > 0 ? num2 / den : kInf);
  return d;
}

double max_sym_rel_err(const std::vector<float>& a, const std::vector<float>& b, double floor) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double d = std::fabs(double(a[i]) - b[i]);
    const double s = std::max(std::fabs(double(a[i])) + std::fabs(double(b[i])), floor);
    m = std::max(m, d / s);
  }
  return m;
}

double max_abs_err(const std::vector<float>& a, const std::vector<float>& b) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::fabs(double(a[i]) - b[i]));
  return m;
}

double norm_err(const std::vector<float>& a, const std::vector<float>& b) {
  double m = 0;
  for (float v : b) m = std::max(m, double(std::fabs(v)));
  return max_abs_err(a, b) / std::max(m, 1e-30);
}

}  // namespace sgnlf::test
