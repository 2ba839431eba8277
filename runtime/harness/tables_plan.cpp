#include "harness/tables_plan.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <tuple>

#include "core/config.hpp"
#include "harness/combine.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;
namespace {

using Key = std::tuple<std::string, std::string, uint64_t>;  // method, sequence, seed

// A committed run as found in some root's results.json.
struct FoundRun {
  std::string results;  // relative to the plan's root
  fs::path scale_dir;
  Json source;          // combined_from.files[k], or the plain result's own description
  std::string config_hash;
  double train_s = -1;
};

std::string short_sha(const Json& sha) {
  return sha.is_string() ? sha.get<std::string>().substr(0, 7) : std::string("?");
}

// Every run of one results table, by (method, sequence, seed).
void collect_runs(const Json& r, const std::string& rel, const fs::path& scale_dir,
                  std::map<Key, FoundRun>& out) {
  const Json files = r.contains("combined_from") ? r["combined_from"].value("files", Json::array())
                                                 : Json::array({source_description(rel, r)});
  for (const auto& row : r.value("rows", Json::array())) {
    if (row.value("status", "") != "ok") continue;
    for (const auto& e : row.value("sequences", Json::array())) {
      for (const auto& x : e.contains("runs") ? e["runs"] : Json::array({e})) {
        // A several-seed entry of a combined table names each seed's source.
        const size_t k = (x.contains("source") ? x : e).value("source", size_t(0));
        if (k >= files.size())
          throw ConfigError(rel + ": row " + row.value("method", "") + " / " + e.value("sequence", "") +
                            ": source " + std::to_string(k) + " is not in combined_from.files");
        FoundRun f{rel, scale_dir, files[k], x.value("config_hash", ""), -1};
        const Json t = x.value("timings", Json::object()).value("train", Json());
        if (t.is_number()) f.train_s = t.get<double>();
        out.emplace(Key{row.value("method", ""), e.value("sequence", ""), x.value("seed", uint64_t(1))}, f);
      }
    }
  }
}

bool selects(const std::vector<std::string>& list, const std::string& x) {
  return list.empty() || std::find(list.begin(), list.end(), x) != list.end();
}

std::string cell_text(const PlanCellRef& c) {
  return c.table + " / " + c.row + " / " + c.sequence + " / seed " + std::to_string(c.seed);
}

bool same_cell(const PlanCellRef& a, const PlanCellRef& b) {
  return a.table == b.table && a.row == b.row && a.sequence == b.sequence && a.seed == b.seed;
}

void fill_provenance(PlannedCell& c, const FoundRun& run, const TablesPlanFile& f) {
  const Json& s = run.source;
  const Json git = s.value("git", Json::object());
  c.committed = true;
  c.results = run.results;
  c.commit = short_sha(git.value("sha", Json())) + (git.value("dirty", Json()) == Json(true) ? " (dirty)" : "");
  const Json bsha = s.value("build_git_sha", Json()), bdirty = s.value("build_git_dirty", Json());
  if (bsha.is_string())
    c.binary = short_sha(bsha) + (bdirty.is_boolean() ? (bdirty.get<bool>() ? " dirty" : " clean") : "");
  const Json dev = s.value("opencl", Json::object()).value("device", Json());
  c.device = dev.is_string() ? dev.get<std::string>() : "?";
  c.other_target = !f.reference_target.empty() && pocl_cpu_target(c.device) != f.reference_target;
  c.config_hash = run.config_hash;
  c.train_s = run.train_s;
  c.run_files = fs::is_directory(run.scale_dir / "runs" / c.ref.row / c.ref.sequence /
                                 ("seed" + std::to_string(c.ref.seed)));
}

}  // namespace

std::string pocl_cpu_target(const std::string& device) {
  const std::string prefix = "pthread-";
  if (device.compare(0, prefix.size(), prefix) != 0) return device;
  for (size_t i = prefix.size(); i + 1 < device.size(); ++i)
    if (device[i] == '-' && std::isupper(static_cast<unsigned char>(device[i + 1])))
      return device.substr(prefix.size(), i - prefix.size());
  return device.substr(prefix.size());
}

size_t PlannedTable::count(const std::string& state) const {
  return size_t(std::count_if(cells.begin(), cells.end(),
                              [&](const PlannedCell& c) { return c.state == state; }));
}

TablesPlan derive_tables_plan(const std::string& root, const TablesPlanFile& f,
                              const BenchHooks& hooks, const std::string& plan_where) {
  TablesPlan plan;
  plan.scale = f.scale;
  for (const auto& name : table_names()) {
    const TableDef def = table_def(name);
    std::map<Key, FoundRun> runs;
    // Earlier roots first: emplace keeps the first root's run of a cell.
    for (const auto& sub : f.roots) {
      const fs::path dir = fs::path(root) / sub / name / f.scale;
      const std::string rel = (fs::path(sub) / name / f.scale / "results.json").lexically_normal().string();
      if (!fs::is_regular_file(dir / "results.json")) continue;
      const Json r = load_json_file((dir / "results.json").string());
      if (!is_results_table(r) || r.value("table", "") != name || r.value("scale", "") != f.scale)
        throw ConfigError(rel + " is not the results table " + name + " at scale " + f.scale);
      collect_runs(r, rel, dir, runs);
    }
    PlannedTable t{name, def.title, {}};
    for (const auto& rd : def.rows) {
      const bool implemented = !hooks.implemented || hooks.implemented(rd.method);
      const std::string current = hooks.config_hash ? hooks.config_hash(rd.method, f.scale) : "";
      for (const auto& sd : table_sequences(def, f.scale, false))
        for (uint64_t seed : f.seeds) {
          PlannedCell c;
          c.ref = PlanCellRef{name, rd.method, sd.name, seed};
          c.label = rd.label;
          c.current_hash = current;
          const auto it = runs.find(Key{rd.method, sd.name, seed});
          if (it != runs.end()) fill_provenance(c, it->second, f);
          if (!implemented)
            c.state = "not implemented";
          else if (c.committed)
            c.state = current.empty() || c.config_hash == current ? "done" : "stale";
          else
            c.state = "to run";
          t.cells.push_back(c);
        }
    }
    plan.tables.push_back(std::move(t));
  }
  // plan.json's intent on top of what the tables say.
  const auto find = [&](const PlanCellRef& ref) -> PlannedCell* {
    for (auto& t : plan.tables)
      for (auto& c : t.cells)
        if (same_cell(c.ref, ref)) return &c;
    return nullptr;
  };
  for (auto& t : plan.tables)
    for (auto& c : t.cells)
      if (c.state == "to run")
        for (const auto& e : f.not_planned)
          if (selects(e.tables, t.name) && selects(e.rows, c.ref.row) &&
              selects(e.sequences, c.ref.sequence) &&
              (e.seeds.empty() || std::count(e.seeds.begin(), e.seeds.end(), c.ref.seed))) {
            c.state = "not planned";
            c.note = e.reason;
            break;
          }
  for (size_t i = 0; i < f.running.size(); ++i) {
    const std::string field = plan_where + ": running[" + std::to_string(i) + "]: ";
    PlannedCell* c = find(f.running[i].cell);
    if (!c) continue;  // plan_file_name_problems names it
    if (c->state == "done")
      plan.problems.push_back(field + cell_text(c->ref) + " is already done at today's config hash " +
                              c->config_hash + " (from " + c->results + ", commit " + c->commit +
                              "): remove it from running");
    else if (c->state == "not implemented" || c->state == "not planned")
      plan.problems.push_back(field + cell_text(c->ref) + " is " + c->state +
                              (c->note.empty() ? "" : " (" + c->note + ")"));
    else {
      c->state = "running";
      c->note = "by " + f.running[i].by + (f.running[i].since.empty() ? "" : ", since " + f.running[i].since);
    }
  }
  for (size_t i = 0; i < f.certified.size(); ++i) {
    PlannedCell* c = find(f.certified[i].cell);
    if (!c) continue;
    if (c->state != "done")
      plan.problems.push_back(plan_where + ": certified[" + std::to_string(i) + "]: " + cell_text(c->ref) +
                              " is " + c->state + ", not done at today's config hash (" +
                              (c->current_hash.empty() ? "unknown" : c->current_hash) +
                              "): a certification holds for a current cell only");
    c->certifies = "at " + f.certified[i].commit.substr(0, 7) + ": " + f.certified[i].how;
  }
  return plan;
}

}  // namespace sgnlf::harness
