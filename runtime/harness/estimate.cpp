#include "harness/estimate.hpp"

#include <cmath>
#include <cstdio>

#include "core/config.hpp"
#include "harness/stats.hpp"

namespace sgnlf::harness {
namespace {

const Json* find_by(const Json& arr, const char* key, const std::string& value) {
  if (!arr.is_array()) return nullptr;
  for (const auto& x : arr)
    if (x.is_object() && x.value(key, std::string()) == value) return &x;
  return nullptr;
}

// The median of a timing (a number, a list or a {reps, median, ...} summary); < 0 if none.
double median_of(const Json& timings, const char* key) {
  if (!timings.is_object() || !timings.contains(key)) return -1;
  const auto reps = repetitions(timings[key]);
  return reps.empty() ? -1 : median(reps);
}

}  // namespace

std::string format_duration(double s) {
  char buf[48];
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 3600) std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else std::snprintf(buf, sizeof buf, "%d h %02d min", int(s / 3600), int(std::fmod(s, 3600) / 60));
  return buf;
}

TableEstimate estimate_table(const TablePlan& plan, const std::string& scale, const Json& previous,
                             const std::string& from) {
  if (!previous.is_object()) throw ConfigError(from + ": not a results JSON (not an object)");
  const std::string table = previous.value("table", std::string());
  const std::string prev_scale = previous.value("scale", std::string());
  if (table != plan.table.name || prev_scale != scale)
    throw ConfigError(from + ": a results file of table '" + table + "' at scale '" + prev_scale +
                      "', not '" + plan.table.name + "' at '" + scale +
                      "': it cannot estimate this run");
  TableEstimate e;
  e.from = from;
  const Json ctx = previous.value("context", Json());
  if (ctx.is_object() && ctx.contains("opencl") && ctx["opencl"].is_object())
    e.device = ctx["opencl"].value("device", std::string());
  const Json rows = previous.value("rows", Json());
  for (const auto& cell : plan.cells) {
    CellEstimate c;
    c.index = cell.index;
    if (const Json* row = find_by(rows, "method", cell.method)) {
      const Json sequences = row->value("sequences", Json());  // find_by points into it
      const Json* seq = find_by(sequences, "sequence", cell.sequence);
      const double cell_s = seq ? median_of(seq->value("timings", Json()), "harness_wall_s") : -1;
      const double row_s = median_of(row->value("timings", Json()), "harness_wall_s");
      if (cell_s >= 0) c.seconds = cell_s, c.basis = "cell";
      else if (row_s >= 0) c.seconds = row_s, c.basis = "row median";
    }
    if (c.seconds >= 0) e.total_s += c.seconds;
    else ++e.unknown;
    e.cells.push_back(c);
  }
  const double prep = median_of(previous.value("timings", Json()), "prepare_s");
  if (prep > 0) e.prepare_s = prep * double(plan.sequences.size());
  e.total_s += e.prepare_s;
  return e;
}

std::string TableEstimate::summary() const {
  std::string s = std::to_string(cells.size()) + " cell(s), estimated " + format_duration(total_s);
  if (unknown) s += " + " + std::to_string(unknown) + " cell(s) never measured";
  s += " (from " + from + (device.empty() ? "" : ", measured on " + device) + ")";
  return s;
}

}  // namespace sgnlf::harness
