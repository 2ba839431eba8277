// Markdown rendering of a results JSON (results/schema.md): the table with our numbers beside
// the paper's and the differences, "not implemented" / "failed" rows kept in place,
// per-sequence tables, timings and the run's context.
#pragma once
#include <cstdint>
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

// Formats a metric value with the table file's digits ("—" for null/missing).
std::string format_metric(const std::string& key, const Json& v);
std::string render_markdown(const Json& results);
// The seeds of a row's runs, for its label: "" when every sequence ran `table_seed` alone;
// "seeds 1, 2" when every sequence ran those (or "seed 2" alone); else the most seeds a
// sequence ran and on how many ("seeds 1, 2 on 3 of 4 sequences").
std::string seeds_mark(const Json& row, uint64_t table_seed);
// A combined table's provenance (results/schema.md "Combined tables"): the source files and,
// per row, which sequences came from which and whether their config is stale. "" for a
// result that is not combined.
std::string render_provenance(const Json& results);

}  // namespace sgnlf::harness
