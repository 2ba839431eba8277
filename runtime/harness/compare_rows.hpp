// Inside `sgnlf compare` (harness/compare.hpp), shared by compare.cpp and compare_rows.cpp only:
// the walk over a baseline's rows, sequences, seed runs and timings that holds the new result to
// the tolerances of a mode already chosen (compare.cpp chooses it: deterministic twins, a smoke
// table on another device), a loose comparison's allowance for the spread over seeds, and the
// look-ups of result JSON of any shape both files use. Not part of the harness's API.
#pragma once
#include <cstddef>
#include <string>

#include "core/config_fwd.hpp"
#include "core/json_lookup.hpp"
#include "harness/compare.hpp"

namespace sgnlf::harness::compare_detail {

// Null for a missing key or a non-object (core/json_lookup.hpp): never throws.
constexpr auto at = &member_or_null;

// Typed look-ups that never throw: a results file of another shape (hand-edited, truncated, from
// another tool) compares as missing rows and metrics instead of a JSON type_error.
std::string str(const Json& j, const std::string& k);
const Json& arr(const Json& j, const std::string& k);
// The element of array `arr` whose `key` is `value` (nullptr when none is).
const Json* find_by(const Json& arr, const std::string& key, const std::string& value);
// The run of `seed` in a several-seed entry's runs[] (nullptr when it has none).
const Json* run_of_seed(const Json& entry, const Json& seed);

// A side's spread over seeds for one set of metrics: per-metric sample standard deviations
// over `n` seeds (results/schema.md "Several seeds"); n < 2 = one seed, no spread.
struct Spread {
  const Json* sd = nullptr;
  size_t n = 0;
};

// Adds findings to `rep`, judged in rep.mode.
struct Comparer {
  const CompareOptions& opt;
  CompareReport& rep;

  void add(const std::string& kind, bool fails, const std::string& where, const std::string& msg) {
    rep.findings.push_back({kind, fails, where, msg});
  }

  // Every numeric metric of `base` against `fresh` (a missing, non-finite, worse, better or
  // changed one is a finding), allowing the seeds' spread when loose.
  void metrics(const std::string& where, const Json& fresh, const Json& base,
               Spread fresh_spread = {}, Spread base_spread = {});
  // Each timing's median against the baseline's, on the same device with enough repetitions.
  void timings(const std::string& where, const Json& fresh, const Json& base, bool same_dev,
               int min_reps, double max_ratio);
};

// Every row, sequence, seed run and timing of `base` against `fresh`, in c.rep.mode.
void compare_rows(Comparer& c, const Json& fresh, const Json& base, bool same_dev, int min_reps,
                  double max_ratio);

}  // namespace sgnlf::harness::compare_detail
