// Repetition statistics for timings (results/schema.md, "timing summary"): the raw
// repetitions plus their count, median, min and max.
#pragma once
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

double median(std::vector<double> v);  // throws on an empty vector
// {"reps": [...], "n", "median", "min", "max"} (seconds unless the caller says otherwise).
Json summarize(const std::vector<double>& reps);
// Reads a repetitions list back from a summary, a bare number or an array of numbers.
std::vector<double> repetitions(const Json& timing);

}  // namespace sgnlf::harness
