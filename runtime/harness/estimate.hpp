// How long a table run will take, estimated before it starts from a previous run of the same
// table and scale: each planned cell takes what that row × sequence took then (its
// harness_wall_s, per seed), else the row's median over its sequences; sequence preparation
// adds the previous median prepare time per sequence. `sgnlf bench` prints the estimate first,
// so a user knows whether a reproduction takes minutes or a day (results/schema.md "timings").
#pragma once
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "harness/runner.hpp"

namespace sgnlf::harness {

struct CellEstimate {
  size_t index = 0;
  double seconds = -1;  // < 0: no previous measurement of this row
  std::string basis;    // "cell" | "row median" | "" (unknown)
};

struct TableEstimate {
  std::vector<CellEstimate> cells;
  double prepare_s = 0;  // preparing the sequences once
  double total_s = 0;    // cells with a measurement + preparation
  size_t unknown = 0;    // cells without one
  std::string from;      // the previous results file
  std::string device;    // the OpenCL device it was measured on
  std::string summary() const;  // one line
};

// `previous` is a results.json of the same table and scale (ConfigError otherwise); `from`
// names it in the summary.
TableEstimate estimate_table(const TablePlan& plan, const std::string& scale, const Json& previous,
                             const std::string& from);

// "2 h 05 min", "14 min", "40 s".
std::string format_duration(double seconds);

}  // namespace sgnlf::harness
