#include "harness/combine.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "core/config.hpp"
#include "harness/cells.hpp"
#include "harness/clock.hpp"
#include "harness/results.hpp"
#include "harness/schema.hpp"
#include "harness/stats.hpp"

namespace sgnlf::harness {
namespace {

const Json& at_path(const Json& j, std::initializer_list<const char*> path) {
  static const Json null_json;
  const Json* p = &j;
  for (const char* k : path) {
    if (!p->is_object() || !p->contains(k)) return null_json;
    p = &(*p)[k];
  }
  return *p;
}

std::vector<uint64_t> seeds_of(const Json& r) {
  const Json& c = r["config"];
  if (c.contains("seeds") && c["seeds"].is_array()) return c["seeds"].get<std::vector<uint64_t>>();
  return {c.value("seed", uint64_t(1))};
}

// A run entry without what may differ between two equal runs, nor its provenance.
Json comparable_entry(const Json& e) {
  const Json wrapped{{"rows", Json::array({Json{{"sequences", Json::array({e})}}})}};
  Json v = comparable_view(wrapped)["rows"][0]["sequences"][0];
  for (const char* k : {"source", "stale"}) v.erase(k);
  return v;
}

// One input's run of a cell (row × sequence × seed): a one-seed run entry.
struct Claim {
  size_t input = 0, source = 0;
  Json entry;
};

using CellKey = std::tuple<std::string, std::string, uint64_t>;  // method, sequence, seed

}  // namespace

bool is_results_table(const Json& r) {
  return r.is_object() && r.value("schema", Json()) == Json(kSchemaName) &&
         r.value("kind", Json()) == Json("table");
}

Json source_description(const std::string& path, const Json& r) {
  return Json{{"file", path},
              {"command", r.value("command", "")},
              {"created_utc", r.value("created_utc", "")},
              {"config_hash", r.value("config_hash", "")},
              {"git", Json{{"sha", at_path(r, {"context", "git", "sha"})},
                           {"dirty", at_path(r, {"context", "git", "dirty"})}}},
              {"build_git_sha", at_path(r, {"context", "build", "git", "sha"})},
              {"build_git_dirty", at_path(r, {"context", "build", "git", "dirty"})},
              {"opencl", Json{{"device", at_path(r, {"context", "opencl", "device"})},
                              {"driver_version", at_path(r, {"context", "opencl", "driver_version"})}}}};
}

Json combine_tables(const std::vector<std::pair<std::string, Json>>& inputs,
                    const CombineOptions& opt, const BenchHooks& hooks, const std::string& command,
                    const std::string& out_dir) {
  if (inputs.empty()) throw ConfigError("merge: no results given");
  for (const auto& [path, r] : inputs) {
    if (!is_results_table(r) || r.value("schema_version", Json()) != Json(kSchemaVersion))
      throw ConfigError("merge: " + path + " is not an " + std::string(kSchemaName) + " v" +
                        std::to_string(kSchemaVersion) + " table (sgnlf bench's results.json)");
    for (const char* k : {"table", "scale", "data"})
      if (!r.contains(k) || !r[k].is_string())
        throw ConfigError("merge: " + path + ": field '" + k + "' is missing or not a string");
    if (!r.contains("config") || !r["config"].is_object() || !r.contains("rows") ||
        !r["rows"].is_array())
      throw ConfigError("merge: " + path + ": 'config' or 'rows' is missing");
  }
  const auto& [ref_path, ref] = inputs.front();
  for (const auto& [path, r] : inputs) {
    for (const char* k : {"table", "scale", "data"})
      if (r[k] != ref[k] && !(std::string(k) == "table" && opt.share_cells))
        throw ConfigError("merge: " + ref_path + " and " + path + " are of different " + k + ": " +
                          ref[k].dump() + " vs " + r[k].dump() +
                          (std::string(k) == "table" ? " (--share-cells takes another table's "
                                                       "runs of this table's rows)"
                                                     : ""));
  }
  const TableDef def = table_def(ref["table"].get<std::string>());
  const std::string scale = ref["scale"].get<std::string>();
  const bool real = ref["data"] == "real";
  const auto def_seqs = table_sequences(def, scale, real);
  const Json own_table = ref["table"];  // a copy: a lambda may not capture a structured binding
  const auto is_foreign = [&](const Json& r) { return r["table"] != own_table; };
  // Another table's sequence is this table's when this build defines both alike (name, preset,
  // frequency, frames, width, window, real folder): the same training and evaluation.
  // Returns "" when alike, else why not.
  const auto unlike = [&](const TableDef& other, const std::string& sq) -> std::string {
    const auto mine = std::find_if(def_seqs.begin(), def_seqs.end(),
                                   [&](const SequenceDef& d) { return d.name == sq; });
    if (mine == def_seqs.end()) return "not a sequence of " + def.name + " at scale " + scale;
    for (const auto& d : table_sequences(other, scale, real))
      if (d.name == sq)
        return d.to_json() == mine->to_json() ? "" : "defined otherwise in " + def.name;
    return "not a sequence of " + other.name + " at scale " + scale;
  };
  const auto alike = [&](const TableDef& other, const std::string& sq) { return unlike(other, sq).empty(); };
  Json shared = Json::array();  // per foreign input: {input, table, taken, left_out}
  // The table's seeds: every input's, in order of first appearance (a one-seed table merged
  // with another seed's becomes a several-seed table; results/schema.md "Combined tables").
  std::vector<uint64_t> seeds;
  for (const auto& in : inputs)
    for (uint64_t k : seeds_of(in.second))
      if (std::find(seeds.begin(), seeds.end(), k) == seeds.end()) seeds.push_back(k);
  const auto seed_rank = [&](uint64_t k) {
    return size_t(std::find(seeds.begin(), seeds.end(), k) - seeds.begin());
  };
  const auto seq_known = [&](const std::string& n) {
    return std::any_of(def_seqs.begin(), def_seqs.end(),
                       [&](const SequenceDef& d) { return d.name == n; });
  };

  // Sources: one per plain input, and the sources a combined input already carries.
  Json files = Json::array();
  const auto add_source = [&](const Json& d) {
    for (size_t i = 0; i < files.size(); ++i)
      if (files[i] == d) return i;
    files.push_back(d);
    return files.size() - 1;
  };
  std::map<CellKey, std::vector<Claim>> claims;
  std::map<std::string, Json> failures;  // method -> [{source, error}]
  Json superseded = Json::array();
  Json reproduced = Json::array();  // equal runs of one cell from several sources
  for (size_t i = 0; i < inputs.size(); ++i) {
    // Named references, not a structured binding: the lambda below captures them (C++17 does
    // not let a lambda capture a structured binding; clang refuses it).
    const std::string& path = inputs[i].first;
    const Json& r = inputs[i].second;
    const Json& earlier = at_path(r, {"combined_from", "files"});
    // Another table's input (--share-cells) brings only the runs taken from it: its sources are
    // added when a run needs one, each marked with the table and the file it came through.
    const bool foreign = is_foreign(r);
    const TableDef other = foreign ? table_def(r["table"].get<std::string>()) : TableDef{};
    Json taken = Json::array(), left_out = Json::array();
    std::map<size_t, size_t> local;  // the input's source index -> ours
    const auto describe = [&](Json d) {
      if (foreign) {
        d["table"] = r["table"];
        d["via"] = path;
      }
      return add_source(d);
    };
    if (earlier.is_array() && !foreign)
      for (size_t k = 0; k < earlier.size(); ++k) local[k] = add_source(earlier[k]);
    const size_t own = earlier.is_array() || foreign ? 0 : add_source(source_description(path, r));
    const auto source_of = [&](const Json& j) {
      if (!earlier.is_array()) return foreign ? describe(source_description(path, r)) : own;
      const size_t k = j.value("source", size_t(0));
      if (k >= earlier.size())
        throw ConfigError("merge: " + path + ": source " + std::to_string(k) + " out of range");
      if (!local.count(k)) local[k] = describe(earlier[k]);
      return local[k];
    };
    if (!foreign)  // another table's history of its own cells is not this table's
      for (const char* list : {"superseded", "reproduced"})
        for (const auto& s : at_path(r, {"combined_from", list})) {
          Json x = s;
          x["source"] = source_of(Json{{"source", s.value("source", 0)}});
          x["by"] = source_of(Json{{"source", s.value("by", 0)}});
          (std::string(list) == "superseded" ? superseded : reproduced).push_back(x);
        }
    for (const auto& row : r["rows"]) {
      const std::string m = row.value("method", ""), st = row.value("status", "");
      const bool data = st == "ok" || st == "failed" || row.contains("failures");
      if (!data) continue;  // not run, not implemented: nothing to carry
      const bool mine =
          std::any_of(def.rows.begin(), def.rows.end(), [&](const RowDef& d) { return d.method == m; });
      if (foreign && (!mine || st != "ok")) {  // only this table's rows' runs are taken
        left_out.push_back(Json{{"method", m}, {"why", !mine ? "not a row of " + def.name : "status " + st}});
        continue;
      }
      if (!mine)
        throw ConfigError("merge: " + path + ": row '" + m + "' is not a row of table " + def.name +
                          " in this build (sgnlf bench --list)");
      for (const auto& f : row.value("failures", Json::array()))
        failures[m].push_back(Json{{"source", source_of(f)}, {"error", f.value("error", "")}});
      if (st == "failed" && !earlier.is_array())
        failures[m].push_back(Json{{"source", own}, {"error", row.value("error", "")}});
      if (st != "ok") continue;
      for (const auto& e : row.value("sequences", Json::array())) {
        const std::string sq = e.value("sequence", "");
        if (const std::string why = foreign ? unlike(other, sq) : ""; !why.empty()) {
          left_out.push_back(Json{{"method", m}, {"sequence", sq}, {"why", why}});
          continue;
        }
        if (foreign) taken.push_back(Json{{"method", m}, {"sequence", sq}});
        if (!seq_known(sq))
          throw ConfigError("merge: " + path + ": row " + m + " ran sequence '" + sq +
                            "', not a sequence of table " + def.name + " at scale " + scale +
                            " in this build (sgnlf bench --list)");
        // One claim per seed: a several-seed entry's runs (each with its own source when it
        // came from a combined table, else the entry's), or the one-seed entry itself.
        for (const auto& run : e.contains("runs") && e["runs"].is_array() ? e["runs"] : Json::array({e})) {
          Json x = run;
          const size_t src = source_of(run.contains("source") ? run : e);
          x.erase("source");
          x.erase("stale");
          x["sequence"] = sq;
          claims[{m, sq, run.value("seed", uint64_t(1))}].push_back(Claim{i, src, x});
        }
      }
    }
    if (foreign)
      shared.push_back(Json{{"input", path}, {"table", r["table"]}, {"taken", taken},
                            {"left_out", left_out}});
  }
  // One claim per row × sequence × seed: equal duplicates are one run, recorded as reproduced
  // (a rerun that certifies the cell), the later one's provenance taken with --later-wins;
  // different ones are refused unless the later input wins.
  std::map<CellKey, Claim> chosen;
  for (const auto& [key, list] : claims) {
    // Copies, not structured bindings: a lambda may not capture those in C++17 (clang refuses).
    const std::string method = std::get<0>(key), sequence = std::get<1>(key);
    const uint64_t seed = std::get<2>(key);
    const auto record = [&](Json& to, const Claim& was, const Claim& by) {
      to.push_back(Json{{"method", method}, {"sequence", sequence}, {"seed", seed},
                        {"source", was.source}, {"by", by.source}});
    };
    Claim c = list.front();
    for (size_t k = 1; k < list.size(); ++k) {
      if (comparable_entry(list[k].entry) == comparable_entry(c.entry)) {
        if (list[k].source == c.source) continue;
        record(reproduced, c, list[k]);
        if (opt.later_wins) c = list[k];
        continue;
      }
      if (!opt.later_wins)
        throw ConfigError("merge: " + method + " / " + sequence + " / seed " + std::to_string(seed) +
                          " is in both " + inputs[c.input].first + " and " +
                          inputs[list[k].input].first +
                          " with different results (order the inputs and give --later-wins to "
                          "let the later one replace the earlier)");
      record(superseded, c, list[k]);
      c = list[k];
    }
    chosen[key] = c;
  }

  std::vector<std::string> real_names;
  for (const auto& sd : def_seqs)
    if (!real && sd.is_real_dir()) real_names.push_back(sd.name);
  Json rows = Json::array(), runs = Json::array();
  std::set<std::string> ran;
  for (const auto& rd : def.rows) {
    const std::string current = hooks.config_hash ? hooks.config_hash(rd.method, scale) : "";
    std::vector<Json> flat;
    std::map<std::string, std::vector<const Claim*>> of_seq;
    Json not_run = Json::array();
    for (const auto& sd : def_seqs) {
      std::vector<const Claim*> cs;
      for (auto it = chosen.lower_bound({rd.method, sd.name, 0});
           it != chosen.end() && std::get<0>(it->first) == rd.method && std::get<1>(it->first) == sd.name; ++it)
        cs.push_back(&it->second);
      if (cs.empty()) {
        not_run.push_back(sd.name);
        continue;
      }
      // The cell's seeds in the table's seed order.
      std::stable_sort(cs.begin(), cs.end(), [&](const Claim* a, const Claim* b) {
        return seed_rank(a->entry.value("seed", uint64_t(1))) < seed_rank(b->entry.value("seed", uint64_t(1)));
      });
      ran.insert(sd.name);
      of_seq[sd.name] = cs;
      for (const Claim* c : cs) {
        Json run = c->entry;
        run["source"] = c->source;
        flat.push_back(run);
        runs.push_back(Json{{"method", rd.method}, {"sequence", sd.name},
                            {"seed", run.value("seed", Json())},
                            {"dataset_seed", at_path(run, {"dataset", "seed"})}});
      }
    }
    const Json fails = failures.count(rd.method) ? failures[rd.method] : Json::array();
    std::string status = !flat.empty()      ? "ok"
                         : !fails.empty()   ? "failed"
                         : !hooks.implemented || hooks.implemented(rd.method) ? "not_run"
                                                                              : "not_implemented";
    const std::string error = status == "failed" ? fails.back().value("error", "") : "";
    Json row = make_row(def.name, rd, status, flat, error, real_names);
    // Provenance and staleness of each run kept: a several-seed entry's runs keep their own
    // sources (the seeds may come from different inputs), and the entry names its first seed's.
    Json stale_any = of_seq.empty() || current.empty() ? Json(nullptr) : Json(false);
    std::set<size_t> srcs;
    for (auto& e : row["sequences"]) {
      const auto& cs = of_seq.at(e.value("sequence", ""));
      e["source"] = cs.front()->source;
      std::vector<Json> hs;
      for (const Claim* c : cs) {
        srcs.insert(c->source);
        hs.push_back(c->entry.value("config_hash", Json()));
      }
      if (current.empty()) {
        e["stale"] = nullptr;
        continue;
      }
      e["stale"] = std::any_of(hs.begin(), hs.end(), [&](const Json& h) { return h != Json(current); });
      if (e["stale"] == Json(true)) stale_any = true;
    }
    row["sources"] = srcs;
    row["sequences_not_run"] = not_run;
    row["current_config_hash"] = current.empty() ? Json(nullptr) : Json(current);
    row["stale"] = stale_any;
    if (!fails.empty()) row["failures"] = fails;
    rows.push_back(row);
  }

  // The table's sequences: those some row ran (as the first input holding them describes
  // them), the others in skipped_sequences with the reason.
  Json seq_list = Json::array(), skipped = Json::array();
  for (const auto& sd : def_seqs) {
    Json found, skip;
    for (const auto& [path, r] : inputs) {
      if (is_foreign(r)) {  // only a sequence defined alike, and no skip reason of its table's
        if (found.is_null() && alike(table_def(r["table"].get<std::string>()), sd.name))
          for (const auto& s : r.value("sequences", Json::array()))
            if (found.is_null() && s.value("name", "") == sd.name) found = s;
        continue;
      }
      for (const auto& s : r.value("sequences", Json::array()))
        if (found.is_null() && s.value("name", "") == sd.name) found = s;
      for (const auto& s : r.value("skipped_sequences", Json::array()))
        if (skip.is_null() && s.value("name", "") == sd.name) skip = s;
    }
    if (ran.count(sd.name) && !found.is_null()) {
      seq_list.push_back(found);
    } else {
      if (skip.is_null()) {
        skip = Json{{"name", sd.name}, {"path", ""}, {"reason", "not run: no input has a run of it"}};
        if (sd.is_real_dir()) skip["real_dir"] = sd.real_dir;
      }
      skipped.push_back(skip);
    }
  }

  Json config = ref["config"];
  config.erase("rows");
  config.erase("sequences");
  if (seeds.size() > 1) {  // as bench --seeds writes it
    config.erase("seed");
    config["seeds"] = seeds;
  }
  std::vector<double> prepare;
  double total = 0;
  long rss = 0;
  Json metric_definitions, real_root;
  for (const auto& [path, r] : inputs) {
    if (is_foreign(r)) continue;  // its timings are its own table's
    const Json& p = at_path(r, {"timings", "prepare_s"});
    if (!p.is_null())
      for (double x : repetitions(p)) prepare.push_back(x);
    const Json& t = at_path(r, {"timings", "total_s"});
    if (t.is_number()) total += t.get<double>();
    rss = std::max(rss, r.value("peak_rss_kib", 0L));
    if (metric_definitions.is_null()) metric_definitions = r.value("metric_definitions", Json());
    if (real_root.is_null()) real_root = r.value("real_root", Json());
  }
  Json out;
  out["schema"] = kSchemaName;
  out["schema_version"] = kSchemaVersion;
  out["kind"] = "table";
  out["table"] = def.name;
  out["title"] = def.title;
  out["scale"] = scale;
  out["data"] = ref["data"];
  out["created_utc"] = utc_now();
  out["command"] = command;
  out["out_dir"] = out_dir;
  out["config"] = config;
  out["config_hash"] = config_hash(config);
  out["seeds"] = Json{{"table_seed", seeds.front()}, {"runs", runs}};
  if (seeds.size() > 1) out["seeds"]["table_seeds"] = seeds;
  out["context"] = ref.value("context", Json::object());
  out["columns"] = def.columns;
  out["extra_columns"] = def.extra_columns;
  out["metric_definitions"] = metric_definitions;
  out["sequences"] = seq_list;
  out["skipped_sequences"] = skipped;
  if (!real_names.empty()) out["real_root"] = real_root.is_null() ? Json("") : real_root;
  out["rows"] = rows;
  out["timings"] = Json{{"total_s", total}};
  if (!prepare.empty()) out["timings"]["prepare_s"] = summarize(prepare);
  out["peak_rss_kib"] = rss;
  Json in_paths = Json::array();
  for (const auto& in : inputs) in_paths.push_back(in.first);
  out["combined_from"] = Json{{"inputs", in_paths}, {"files", files},
                              {"later_wins", opt.later_wins}, {"superseded", superseded},
                              {"reproduced", reproduced}};
  if (!shared.empty()) out["combined_from"]["shared"] = shared;
  return out;
}

}  // namespace sgnlf::harness
