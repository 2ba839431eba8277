// The README's tables: one compact table per committed table (results/tables/<table>/<scale>/
// results.json), the row means of the headline metrics beside the paper's, generated here so
// that the manual's numbers are the committed ones. `sgnlf check-tables --readme README.md`
// fails when the README's marked section differs from this rendering (`--render` rewrites it).
#pragma once
#include <string>

#include "core/config_fwd.hpp"

namespace sgnlf::harness {

// One table: "**title** ([link](link))" and a row per table row: ours | paper for CD, F-score,
// depth RMSE, intensity PSNR and ATE, ours "mean ± sd" where the row has a spread over seeds
// (`mean_sd`); a row's status ("not implemented", "not run", "failed"), its seeds when not the
// table's one seed ("seeds 1, 2", markdown.hpp seeds_mark), "stale preset" and "k of n
// sequences" marks. `link` is the table.md path the heading links.
std::string summary_markdown(const Json& results, const std::string& link);

// Every <root>/<table>/<scale>/results.json of the tables `sgnlf bench --list` defines, in that
// order, with links under `link_root` (e.g. "results/tables"), then the paper's claims beside
// ours (harness/claims.hpp, from the same tables).
std::string summary_tables(const std::string& root, const std::string& scale,
                           const std::string& link_root);

// The README section between kReadmeBegin and kReadmeEnd replaced by `section`; ConfigError
// naming `file` when a marker is missing.
extern const char* const kReadmeBegin;
extern const char* const kReadmeEnd;
std::string replace_marked_section(const std::string& text, const std::string& section,
                                   const std::string& file);

}  // namespace sgnlf::harness
