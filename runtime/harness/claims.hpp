// The paper's claims beside ours (the README's "claims" part of its generated tables section):
// each claim of results/paper_tables.json "claims" is a relative change of one metric between
// two rows of one table (SG-NLF against GeoNLF on CD, an ablation row against the full method,
// ...). Ours is computed from the committed tables over the twins both rows ran (real sequences
// are averaged apart in the tables, and left out here), a cell run with several seeds counting
// with its seed mean; beside it, the same change from each seed's runs alone.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

struct Claim {
  std::string text;    // "SG-NLF vs GeoNLF, CD" as printed
  std::string table;   // a table of `sgnlf bench --list`
  std::string metric;  // a metric of tables.json
  std::string row, against;  // methods: the claim is (row − against) / against
  double paper_change = 0;   // the paper's relative change, e.g. -0.358
  std::string source;        // where the paper says it
  std::string note;          // what our tables suggest as the cause of a difference ("" = none)
};

// The claims of the embedded paper_tables.json, validated (unknown keys, unknown tables, rows
// or metrics rejected with ConfigError naming the claim and field).
std::vector<Claim> paper_claims();
std::vector<Claim> parse_claims(const Json& claims, const std::string& where);

// Our relative change for one claim from one results.json, over the non-real sequences both
// rows ran with the metric a number (a several-seed entry's seed mean): {"change", "sequences"
// (count), "of" (the table's non-real sequences)}; "change" null when the rows share none,
// "status" naming why.
Json claim_change(const Claim& c, const Json& results);
// The same from the runs of one seed alone (a sequence either row did not run with `seed`
// does not count).
Json claim_change_of_seed(const Claim& c, const Json& results, uint64_t seed);
// Whether `method`'s row of a results table holds a stale run (made with an older preset: the
// row's or a sequence entry's "stale" flag, as sgnlf merge sets them). A claim over a stale row
// compares two presets and is marked so, not judged.
bool claim_row_stale(const Json& results, const std::string& method);
// The evaluation rules `method`'s runs were scored by, as text: "expected depth", "median
// depth" or "mix depth" (render.eval_depth, "expected" when the config omits it), and ", out-of-
// range drops" where render.eval_drop_out_of_range is on; several sets joined by " / " (a row
// whose runs differ). Empty when the row has no run with a config. A claim on a view metric over
// two rows scored by different rules compares the rules as much as the methods, and is marked
// so, not judged (a pose metric does not depend on them).
std::string claim_row_rules(const Json& results, const std::string& method);
// A results table's seeds: config.seeds, else [config.seed].
std::vector<uint64_t> table_seeds(const Json& results);

// The markdown of every claim: a table (claim, paper, ours, by seed, agreement) and the notes
// under it. `root`: <root>/<table>/<scale>/results.json (a missing file: "not run").
std::string claims_markdown(const std::string& root, const std::string& scale);

}  // namespace sgnlf::harness
