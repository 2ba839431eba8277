// The table's results JSON assembled from its cells' outcomes.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"
#include "harness/plan.hpp"

namespace sgnlf::harness {

// The table's results JSON from the cells' outcomes (indexed like plan.cells; a cell may be
// absent only after its row stopped or its sequence was skipped). Replays the one-process
// order, so that the cells run apart and merged give the same rows as run_table.
struct TableHeader {
  Json config;  // BenchOptions::to_json()
  std::string command, out_dir, real_root;
  bool real = false;  // --data-root
  Json metric_definitions, context;
  double total_s = 0;
  long peak_rss_kib = 0;
};
Json assemble_table(const TablePlan& plan, const std::vector<CellOutcome>& outcomes,
                    const TableHeader& header);

}  // namespace sgnlf::harness
