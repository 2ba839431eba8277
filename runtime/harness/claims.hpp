// The paper's claims beside ours (the README's "claims" part of its generated tables section):
// each claim of results/paper_tables.json "claims" is a relative change of one metric between
// two rows of one table (SG-NLF against GeoNLF on CD, an ablation row against the full method,
// ...). Ours is computed from the committed tables over the twins both rows ran (real sequences
// are averaged apart in the tables, and left out here), at seed 1 and, where a second seed's
// table holds either row, with that seed's means too.
#pragma once
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
// rows ran with the metric a number: {"change", "sequences" (count), "of" (the table's
// non-real sequences)}; "change" null when the rows share none, "status" naming why.
Json claim_change(const Claim& c, const Json& results);
// Like claim_change, with each row's per-sequence values taken from `seed2` where it has that
// row and sequence, else from `seed1`.
Json claim_change_mixed(const Claim& c, const Json& seed1, const Json& seed2);

// The markdown of every claim: a table (claim, paper, ours, with a second seed, agreement) and
// the notes under it. `root`: <root>/<table>/<scale>/results.json; `seed2_root` the same
// layout for seed 2 ("" or a missing file: none).
std::string claims_markdown(const std::string& root, const std::string& scale,
                            const std::string& seed2_root);

}  // namespace sgnlf::harness
