#include "harness/summary_table.hpp"

#include <algorithm>
#include <cstdio>
#include <vector>
#include <filesystem>

#include "core/config.hpp"
#include "harness/claims.hpp"
#include "harness/markdown.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace {

struct Column {
  const char* key;
  const char* title;
  int digits;
};
constexpr Column kColumns[] = {{"cd", "CD (m²) ↓", 3},
                               {"fscore", "F-score ↑", 3},
                               {"depth_rmse", "depth RMSE (m) ↓", 2},
                               {"intensity_psnr", "intensity PSNR (dB) ↑", 2},
                               {"ate_m", "ATE (m) ↓", 3}};

std::string fixed(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

const Json& member(const Json& j, const char* k) {
  static const Json null_json;
  return j.is_object() && j.contains(k) ? j[k] : null_json;
}

// The paper's number of a row (verified first, else a third-party one marked †), or "".
std::string paper_cell(const Json& row, const Column& c) {
  const Json& p = member(member(row, "paper"), c.key);
  if (p.is_number()) return fixed(p.get<double>(), c.digits);
  const Json& u = member(member(row, "paper_unverified"), c.key);
  if (u.is_number()) return fixed(u.get<double>(), c.digits) + "†";
  return "";
}

std::string status_text(const std::string& s) {
  if (s == "not_implemented") return "not implemented";
  if (s == "not_run") return "not run";
  return s;
}

}  // namespace

const char* const kReadmeBegin =
    "<!-- tables: made by `sgnlf check-tables --render --readme README.md`; do not edit -->";
const char* const kReadmeEnd = "<!-- end of tables -->";

std::string summary_markdown(const Json& results, const std::string& link) {
  std::string md = "**" + member(results, "title").get<std::string>() + "** ([" + link + "](" +
                   link + "))\n\n| row |";
  std::string rule = "|---|";
  for (const auto& c : kColumns) {
    md += std::string(" ") + c.title + " ours | paper |";
    rule += "---:|---:|";
  }
  md += "\n" + rule + "\n";
  const size_t n_seq = member(results, "sequences").size() +
                       member(results, "skipped_sequences").size();
  for (const auto& row : member(results, "rows")) {
    const std::string status = member(row, "status").is_string() ? row["status"].get<std::string>() : "";
    std::string label = member(row, "label").is_string() ? row["label"].get<std::string>() : "";
    std::vector<std::string> marks;
    if (status == "ok") {  // its seeds, when not the table's one seed alone
      const std::string m = seeds_mark(row, table_seeds(results).front());
      if (!m.empty()) marks.push_back(m);
    }
    if (member(row, "stale").is_boolean() && row["stale"].get<bool>()) marks.push_back("stale preset");
    const size_t not_run = member(row, "sequences_not_run").size();
    if (status == "ok" && not_run > 0 && n_seq > not_run)
      marks.push_back(std::to_string(n_seq - not_run) + " of " + std::to_string(n_seq) + " sequences");
    for (size_t i = 0; i < marks.size(); ++i) label += (i ? "; " : " (") + marks[i];
    if (!marks.empty()) label += ")";
    md += "| " + label + " |";
    for (const auto& c : kColumns) {
      std::string ours;
      if (status != "ok") {
        ours = status_text(status);
      } else {
        const Json& v = member(member(row, "mean"), c.key);
        const Json& sd = member(member(row, "mean_sd"), c.key);  // several seeds
        ours = v.is_number() ? fixed(v.get<double>(), c.digits) : "—";
        // One digit more for the spread: a small sd would print as 0.
        if (v.is_number() && sd.is_number()) ours += " ± " + fixed(sd.get<double>(), c.digits + 1);
      }
      md += " " + ours + " | " + paper_cell(row, c) + " |";
    }
    md += "\n";
  }
  return md;
}

std::string summary_tables(const std::string& root, const std::string& scale,
                           const std::string& link_root) {
  // The paper's tables first, the ablation last (as the paper prints them).
  std::vector<std::string> names = table_names();
  std::stable_partition(names.begin(), names.end(),
                        [](const std::string& n) { return n.rfind("ablation", 0) != 0; });
  std::string out;
  for (const auto& name : names) {
    const std::string file = root + "/" + name + "/" + scale + "/results.json";
    if (!std::filesystem::exists(file)) continue;
    out += (out.empty() ? "" : "\n") +
           summary_markdown(load_json_file(file), link_root + "/" + name + "/" + scale + "/table.md");
  }
  // The paper's claims beside ours (harness/claims.hpp), from the same tables.
  if (!out.empty()) out += "\n" + claims_markdown(root, scale);
  return out;
}

std::string replace_marked_section(const std::string& text, const std::string& section,
                                   const std::string& file) {
  const size_t b = text.find(kReadmeBegin);
  const size_t e = text.find(kReadmeEnd);
  if (b == std::string::npos || e == std::string::npos || e < b)
    throw ConfigError(file + ": the markers of the generated tables are missing (a line '" +
                      kReadmeBegin + "' and, after it, a line '" + kReadmeEnd + "')");
  const size_t start = b + std::string(kReadmeBegin).size();
  return text.substr(0, start) + "\n\n" + section + "\n" + text.substr(e);
}

}  // namespace sgnlf::harness
