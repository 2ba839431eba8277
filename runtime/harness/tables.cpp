#include "harness/tables.hpp"

#include <algorithm>
#include <filesystem>

#include "core/config.hpp"

namespace sgnlf::harness {
namespace {

const Json& tables_root() {
  static const Json j = [] {
    try {
      return Json::parse(tables_json());
    } catch (const std::exception& e) {
      throw ConfigError(std::string("runtime/harness/tables.json (embedded): ") + e.what());
    }
  }();
  return j;
}

const Json& paper_root() {
  static const Json j = [] {
    try {
      return Json::parse(paper_tables_json());
    } catch (const std::exception& e) {
      throw ConfigError(std::string("results/paper_tables.json (embedded): ") + e.what());
    }
  }();
  return j;
}

std::vector<SequenceDef> parse_list(const Json& j, const std::string& where) {
  std::vector<SequenceDef> out;
  for (size_t i = 0; i < j.size(); ++i)
    out.push_back(parse_sequence_def(j[i], where + "[" + std::to_string(i) + "]"));
  return out;
}

const Json& lookup(const Json& root, const std::string& a, const std::string& b,
                   const std::string& c) {
  static const Json empty = Json::object();
  if (!root.contains(a) || !root[a].contains(b) || !root[a][b].contains(c)) return empty;
  return root[a][b][c];
}

}  // namespace

SequenceDef parse_sequence_def(const Json& j, const std::string& where) {
  SequenceDef s;
  ConfigReader r(j, where);
  r.require("name", s.name).require("preset", s.preset).require("frequency", s.frequency);
  r.get("frames", s.frames).get("width", s.width).get("sequence", s.sequence);
  r.get("start", s.start).get("stride", s.stride).get("test_frames", s.test_frames);
  const bool has_real_dir = r.has("real_dir");
  r.get("real_dir", s.real_dir);
  r.finish();
  if (s.frequency != "standard" && s.frequency != "low")
    throw ConfigError(where + ": frequency '" + s.frequency + "' is not standard|low");
  for (size_t k = 0; k < s.test_frames.size(); ++k) {
    const int p = s.test_frames[k];
    const bool twice = std::find(s.test_frames.begin(), s.test_frames.begin() + long(k), p) !=
                       s.test_frames.begin() + long(k);
    if (p < 0 || (s.frames > 0 && p >= s.frames) || twice)
      throw ConfigError(where + ": test_frames[" + std::to_string(k) + "] = " + std::to_string(p) +
                        (twice ? " is listed twice" : " is not a position in the window") +
                        (s.frames > 0 ? " (0.." + std::to_string(s.frames - 1) + ")" : ""));
  }
  if (has_real_dir) {
    const std::filesystem::path p(s.real_dir);
    bool up = false;
    for (const auto& part : p) up = up || part == "..";
    if (s.real_dir.empty() || p.is_absolute() || up)
      throw ConfigError(where + ": real_dir '" + s.real_dir +
                        "' must be a non-empty folder name relative to the real-data root "
                        "(no leading '/', no '..')");
  }
  return s;
}

Json SequenceDef::to_json() const {
  Json j{{"name", name}, {"preset", preset}, {"frequency", frequency}};
  if (frames) j["frames"] = frames;
  if (width) j["width"] = width;
  if (!sequence.empty()) j["sequence"] = sequence;
  if (start >= 0) j["start"] = start;
  if (stride) j["stride"] = stride;
  if (!test_frames.empty()) j["test_frames"] = test_frames;
  if (!real_dir.empty()) j["real_dir"] = real_dir;
  return j;
}

std::vector<std::string> table_names() {
  std::vector<std::string> names;
  for (auto it = tables_root()["tables"].begin(); it != tables_root()["tables"].end(); ++it)
    names.push_back(it.key());
  return names;
}

std::vector<std::string> scale_names() { return {"smoke", "quick", "paper"}; }

TableDef table_def(const std::string& name) {
  const Json& tables = tables_root()["tables"];
  if (!tables.contains(name)) {
    std::string known;
    for (const auto& n : table_names()) known += (known.empty() ? "" : ", ") + n;
    throw ConfigError("unknown table '" + name + "' (known: " + known + ")");
  }
  const std::string where = "tables.json: tables." + name;
  TableDef t;
  t.name = name;
  ConfigReader r(tables[name], where);
  Json rows, scales, real;
  r.require("title", t.title).require("rows", rows).require("columns", t.columns);
  r.get("extra_columns", t.extra_columns).require("scales", scales).get("real", real);
  r.finish();
  for (size_t i = 0; i < rows.size(); ++i) {
    RowDef row;
    ConfigReader rr(rows[i], where + ".rows[" + std::to_string(i) + "]");
    rr.require("method", row.method).require("label", row.label);
    rr.finish();
    t.rows.push_back(row);
  }
  for (auto it = scales.begin(); it != scales.end(); ++it)
    t.scales[it.key()] = parse_list(it.value(), where + ".scales." + it.key());
  if (!real.is_null()) t.real = parse_list(real, where + ".real");
  for (const auto& s : t.real)
    if (s.is_real_dir())
      throw ConfigError(where + ".real: sequence " + s.name +
                        " sets real_dir; the --data-root windows are read from --data-root");
  return t;
}

std::vector<SequenceDef> table_sequences(const TableDef& t, const std::string& scale, bool real) {
  const auto names = scale_names();
  if (std::find(names.begin(), names.end(), scale) == names.end())
    throw ConfigError("unknown scale '" + scale + "' (known: smoke, quick, paper)");
  if (real) {
    if (t.real.empty()) throw ConfigError("table '" + t.name + "' has no real-data sequences");
    return t.real;
  }
  const auto it = t.scales.find(scale);
  if (it == t.scales.end() || it->second.empty())
    throw ConfigError("table '" + t.name + "' has no sequences for scale '" + scale + "'");
  return it->second;
}

const MetricInfo* metric_info(const std::string& key) {
  static const std::map<std::string, MetricInfo> infos = [] {
    std::map<std::string, MetricInfo> m;
    const Json& metrics = tables_root()["metrics"];
    for (auto it = metrics.begin(); it != metrics.end(); ++it) {
      MetricInfo info;
      info.key = it.key();
      info.better.clear();
      ConfigReader r(it.value(), "tables.json: metrics." + it.key());
      r.require("label", info.label).get("unit", info.unit).get("better", info.better);
      r.get("part_of", info.part_of).get("digits", info.digits);
      r.finish();
      m[it.key()] = info;
    }
    // Directions: a part without its own takes its metric's (parts of parts resolve in turn).
    for (int pass = 0; pass < 4; ++pass)
      for (auto& [k, info] : m)
        if (info.better.empty() && !info.part_of.empty() && m.count(info.part_of))
          info.better = m[info.part_of].better;
    for (auto& [k, info] : m) {
      if (!info.part_of.empty() && !m.count(info.part_of))
        throw ConfigError("tables.json: metrics." + k + ".part_of: '" + info.part_of +
                          "' is not a metric of tables.json");
      if (info.better != "lower" && info.better != "higher" && info.better != "none")
        throw ConfigError("tables.json: metrics." + k + ".better: '" + info.better +
                          "' is not lower|higher|none (or give part_of)");
      info.lower_better = info.better == "lower";
    }
    // Variants: "<prefix><m>" for every metric m above, a part of m.
    const Json& variants = tables_root().value("metric_variants", Json::object());
    std::map<std::string, MetricInfo> derived;
    for (auto v = variants.begin(); v != variants.end(); ++v) {
      if (!v.value().is_string())
        throw ConfigError("tables.json: metric_variants." + v.key() + " is not a string");
      for (const auto& [k, base] : m) {
        MetricInfo info = base;
        info.key = v.key() + k;
        info.label = base.label + " (" + v.value().get<std::string>() + ")";
        info.part_of = k;
        if (!m.count(info.key)) derived[info.key] = info;
      }
    }
    m.insert(derived.begin(), derived.end());
    return m;
  }();
  const auto it = infos.find(key);
  return it == infos.end() ? nullptr : &it->second;
}

Json paper_numbers(const std::string& table, const std::string& method) {
  return lookup(paper_root(), "tables", table, method);
}

std::string paper_source(const std::string& table) {
  const Json& src = paper_root().contains("sources") ? paper_root()["sources"] : Json::object();
  if (src.contains(table) && src[table].is_string()) return src[table].get<std::string>();
  return "protocol §5 (results/paper_tables.json)";
}

Json unverified_numbers(const std::string& table, const std::string& method) {
  return lookup(paper_root(), "unverified", table, method);
}

const Json& tolerance_table() { return tables_root()["tolerances"]; }

}  // namespace sgnlf::harness
