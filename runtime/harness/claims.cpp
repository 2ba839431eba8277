#include "harness/claims.hpp"

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "core/config.hpp"
#include "core/json_lookup.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace {

constexpr auto at = &member_or_null;

std::string percent(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%+.1f %%", 100.0 * v);
  std::string s = buf;
  if (s[0] == '-') s = "−" + s.substr(1);  // the paper's minus sign
  return s;
}

// The row's value of `metric` per sequence it ran (status ok, a number), by sequence name: the
// entry's (a several-seed entry's seed mean), or with `seed` > 0 that seed's run alone.
std::map<std::string, double> row_values(const Json& results, const std::string& method,
                                         const std::string& metric, uint64_t seed = 0) {
  std::map<std::string, double> v;
  if (!at(results, "rows").is_array()) return v;
  for (const auto& row : results["rows"]) {
    if (at(row, "method") != Json(method) || at(row, "status") != Json("ok")) continue;
    if (!at(row, "sequences").is_array()) continue;
    for (const auto& e : row["sequences"]) {
      if (!at(e, "sequence").is_string()) continue;
      const Json* s = seed == 0 ? &e : nullptr;
      if (seed != 0 && at(e, "runs").is_array()) {
        for (const auto& x : e["runs"])
          if (at(x, "seed") == Json(seed)) s = &x;
      } else if (seed != 0 && (at(e, "seed") == Json(seed) || (at(e, "seed").is_null() && seed == 1))) {
        s = &e;  // a one-seed entry (results before seeds were recorded: seed 1)
      }
      if (!s) continue;
      for (const char* block : {"metrics", "pose_metrics"}) {
        const Json& x = at(at(*s, block), metric);
        if (x.is_number()) v[e["sequence"].get<std::string>()] = x.get<double>();
      }
    }
  }
  return v;
}

// The scale's twins (real sequences, averaged apart in the tables, left out).
std::vector<std::string> twin_names(const std::string& table, const std::string& scale) {
  std::vector<std::string> names;
  const TableDef t = table_def(table);
  const auto it = t.scales.find(scale);
  if (it == t.scales.end()) return names;
  for (const auto& s : it->second)
    if (!s.is_real_dir()) names.push_back(s.name);
  return names;
}

Json change_over(const Claim& c, const std::string& scale, const std::map<std::string, double>& a,
                 const std::map<std::string, double>& b) {
  const auto twins = twin_names(c.table, scale);
  double sa = 0, sb = 0;
  int n = 0;
  for (const auto& name : twins) {
    const auto ia = a.find(name), ib = b.find(name);
    if (ia == a.end() || ib == b.end()) continue;
    sa += ia->second;
    sb += ib->second;
    ++n;
  }
  Json out{{"sequences", n}, {"of", twins.size()}, {"change", nullptr}};
  if (n == 0)
    out["status"] = a.empty() ? c.row + " not run" : b.empty() ? c.against + " not run" : "no sequence in common";
  else if (sb == 0)
    out["status"] = "the reference row's mean is 0";
  else
    out["change"] = (sa - sb) / sb;
  return out;
}

std::string scale_of(const Json& results) {
  return at(results, "scale").is_string() ? results["scale"].get<std::string>() : "quick";
}

Json load_if_there(const std::string& path) {
  if (path.empty() || !std::filesystem::is_regular_file(path)) return nullptr;
  return load_json_file(path);
}

}  // namespace

std::vector<Claim> parse_claims(const Json& claims, const std::string& where) {
  if (!claims.is_array()) throw ConfigError(where + ": not an array of claims");
  std::vector<Claim> out;
  const auto tables = table_names();
  for (size_t i = 0; i < claims.size(); ++i) {
    const std::string w = where + "[" + std::to_string(i) + "]";
    Claim c;
    ConfigReader r(claims[i], w);
    r.require("text", c.text).require("table", c.table).require("metric", c.metric);
    r.require("row", c.row).require("against", c.against).require("paper_change", c.paper_change);
    r.require("source", c.source).get("note", c.note);
    r.finish();
    const TableDef t = table_def(c.table);  // ConfigError naming the known tables
    for (const auto* m : {&c.row, &c.against}) {
      bool found = false;
      for (const auto& row : t.rows) found |= row.method == *m;
      if (!found)
        throw ConfigError(w + ": row '" + *m + "' is not a row of table '" + c.table + "'");
    }
    const MetricInfo* info = metric_info(c.metric);
    if (!info || !info->judged())
      throw ConfigError(w + ".metric: '" + c.metric + "' is not a metric with a direction");
    if (!std::isfinite(c.paper_change) || c.paper_change <= -1.0)
      throw ConfigError(w + ".paper_change: " + std::to_string(c.paper_change) +
                        " is not a relative change (> -1)");
    out.push_back(c);
  }
  return out;
}

std::vector<Claim> paper_claims() {
  static const std::vector<Claim> claims = [] {
    Json root;
    try {
      root = Json::parse(paper_tables_json());
    } catch (const std::exception& e) {
      throw ConfigError(std::string("results/paper_tables.json (embedded): ") + e.what());
    }
    return parse_claims(root.contains("claims") ? root["claims"] : Json::array(),
                        "results/paper_tables.json: claims");
  }();
  return claims;
}

Json claim_change(const Claim& c, const Json& results) {
  return change_over(c, scale_of(results), row_values(results, c.row, c.metric),
                     row_values(results, c.against, c.metric));
}

Json claim_change_of_seed(const Claim& c, const Json& results, uint64_t seed) {
  return change_over(c, scale_of(results), row_values(results, c.row, c.metric, seed),
                     row_values(results, c.against, c.metric, seed));
}

bool claim_row_stale(const Json& results, const std::string& method) {
  if (!at(results, "rows").is_array()) return false;
  for (const auto& row : results["rows"]) {
    if (at(row, "method") != Json(method)) continue;
    if (at(row, "stale") == Json(true)) return true;
    if (at(row, "sequences").is_array())
      for (const auto& e : row["sequences"])
        if (at(e, "stale") == Json(true)) return true;
  }
  return false;
}

std::string claim_row_rules(const Json& results, const std::string& method) {
  std::vector<std::string> rules;
  const auto add = [&](const Json& run) {
    const Json& config = at(run, "config");
    if (!config.is_object()) return;
    const Json& render = at(config, "render");
    const Json& depth = at(render, "eval_depth");
    std::string r =
        (depth.is_string() ? depth.get<std::string>() : std::string("expected")) + " depth";
    if (at(render, "eval_drop_out_of_range") == Json(true)) r += ", out-of-range drops";
    if (std::find(rules.begin(), rules.end(), r) == rules.end()) rules.push_back(r);
  };
  if (at(results, "rows").is_array())
    for (const auto& row : results["rows"]) {
      if (at(row, "method") != Json(method) || !at(row, "sequences").is_array()) continue;
      for (const auto& e : row["sequences"]) {
        add(e);
        if (at(e, "runs").is_array())
          for (const auto& r : e["runs"]) add(r);
      }
    }
  std::string out;
  for (size_t i = 0; i < rules.size(); ++i) out += (i ? " / " : "") + rules[i];
  return out;
}

std::vector<uint64_t> table_seeds(const Json& results) {
  const Json& config = at(results, "config");
  if (at(config, "seeds").is_array()) return config["seeds"].get<std::vector<uint64_t>>();
  return {at(config, "seed").is_number_unsigned() ? config["seed"].get<uint64_t>() : uint64_t(1)};
}

std::string claims_markdown(const std::string& root, const std::string& scale) {
  std::string md =
      "**The paper's claims beside ours** (relative change of the row's mean against the "
      "other row's, over the twins both ran, generated from the tables above: a cell run with "
      "several seeds counts with its seed mean; by seed: the same change from one seed's runs "
      "alone, for each seed both rows ran on those twins)\n\n"
      "| claim | paper | ours | by seed | agrees |\n|---|---:|---:|---|---|\n";
  std::string notes;
  for (const auto& c : paper_claims()) {
    const Json table = load_if_there(root + "/" + c.table + "/" + scale + "/results.json");
    std::string ours = "not run", by_seed, agrees = "—";
    if (!table.is_null()) {
      const Json ch = claim_change(c, table);
      if (ch["change"].is_number()) {
        const double v = ch["change"].get<double>();
        ours = percent(v);
        if (ch["sequences"] != ch["of"])
          ours += " (" + ch["sequences"].dump() + " of " + ch["of"].dump() + ")";
        // Each seed whose runs cover the same twins in both rows; nothing to add when that is
        // one seed giving the same number.
        std::vector<std::string> parts;
        bool differs = false;
        for (uint64_t k : table_seeds(table)) {
          const Json chk = claim_change_of_seed(c, table, k);
          if (!chk["change"].is_number() || chk["sequences"] != ch["sequences"]) continue;
          parts.push_back("seed " + std::to_string(k) + ": " + percent(chk["change"].get<double>()));
          differs |= chk["change"] != ch["change"];
        }
        if (differs || parts.size() > 1)
          for (size_t i = 0; i < parts.size(); ++i) by_seed += (i ? "; " : "") + parts[i];
        const bool same_sign = (v < 0) == (c.paper_change < 0);
        char ratio[64];
        std::snprintf(ratio, sizeof ratio, "%.2f", c.paper_change != 0 ? v / c.paper_change : 0.0);
        agrees = same_sign ? std::string("in sign (") + ratio + " × the paper's)"
                           : "no: the opposite sign";
        std::string stale;
        for (const auto* m : {&c.row, &c.against})
          if (claim_row_stale(table, *m)) stale += (stale.empty() ? "" : " and ") + *m;
        const std::string rules_row = claim_row_rules(table, c.row),
                          rules_against = claim_row_rules(table, c.against);
        // The rules score the rendered views; pose metrics do not depend on them.
        const bool view_metric = c.metric.rfind("ate", 0) != 0 && c.metric.rfind("rpe", 0) != 0;
        if (view_metric && !rules_row.empty() && !rules_against.empty() && rules_row != rules_against)
          agrees = "not like for like: " + c.row + " scored by " + rules_row + ", " + c.against +
                   " by " + rules_against;
        if (!stale.empty()) agrees = "not judged: " + stale + " stale (an older preset)";
      } else {
        ours = ch.value("status", std::string("not run"));
      }
    }
    md += "| " + c.text + " | " + percent(c.paper_change) + " | " + ours + " | " + by_seed + " | " +
          agrees + " |\n";
    if (!c.note.empty()) notes += "- " + c.text + ": " + c.note + "\n";
  }
  if (!notes.empty()) md += "\n" + notes;
  return md;
}

}  // namespace sgnlf::harness
