#include "harness/stats.hpp"

#include <algorithm>

#include "core/config.hpp"

namespace sgnlf::harness {

double median(std::vector<double> v) {
  require(!v.empty(), "median of an empty set of repetitions");
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

Json summarize(const std::vector<double>& reps) {
  if (reps.empty()) return Json{{"reps", Json::array()}, {"n", 0}};
  return Json{{"reps", reps},
              {"n", reps.size()},
              {"median", median(reps)},
              {"min", *std::min_element(reps.begin(), reps.end())},
              {"max", *std::max_element(reps.begin(), reps.end())}};
}

std::vector<double> repetitions(const Json& t) {
  std::vector<double> out;
  if (t.is_number()) {
    out.push_back(t.get<double>());
  } else if (t.is_array()) {
    for (const auto& x : t)
      if (x.is_number()) out.push_back(x.get<double>());
  } else if (t.is_object() && t.contains("reps")) {
    return repetitions(t["reps"]);
  }
  return out;
}

}  // namespace sgnlf::harness
