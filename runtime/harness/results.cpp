#include "harness/results.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "harness/stats.hpp"

namespace sgnlf::harness {

std::string config_hash(const Json& config) { return hex64(fnv1a64(config.dump())); }

Json sequence_entry(const std::string& sequence, uint64_t seed, const Json& dataset,
                    const pipeline::MethodResult& r, const std::string& run_dir, double wall_s) {
  Json e;
  e["sequence"] = sequence;
  e["seed"] = seed;
  e["dataset"] = dataset;
  e["run_dir"] = run_dir;
  e["config"] = r.config;
  e["config_hash"] = config_hash(r.config);
  e["per_frame"] = r.per_frame.is_null() ? Json::array() : r.per_frame;
  e["metrics"] = r.metrics.is_null() ? Json::object() : r.metrics;
  e["pose_metrics"] = r.pose_metrics;
  Json timings = r.timings.is_object() ? r.timings : Json::object();
  timings["harness_wall_s"] = wall_s;
  e["timings"] = timings;
  e["extra"] = r.extra;
  return e;
}

namespace {
// metrics ∪ pose_metrics of one sequence entry.
Json all_metrics(const Json& seq) {
  Json m = seq.value("metrics", Json::object());
  const Json pose = seq.value("pose_metrics", Json());
  if (pose.is_object())
    for (auto it = pose.begin(); it != pose.end(); ++it) m[it.key()] = it.value();
  return m;
}
}  // namespace

Json mean_over_sequences(const std::vector<Json>& sequences) {
  std::set<std::string> keys;
  for (const auto& s : sequences) {
    const Json m = all_metrics(s);
    for (auto it = m.begin(); it != m.end(); ++it) keys.insert(it.key());
  }
  Json mean = Json::object();
  for (const auto& k : keys) {
    double sum = 0;
    bool ok = !sequences.empty();
    for (const auto& s : sequences) {
      const Json m = all_metrics(s);
      if (!m.contains(k) || !m[k].is_number()) {
        ok = false;
        break;
      }
      sum += m[k].get<double>();
    }
    mean[k] = ok ? Json(sum / double(sequences.size())) : Json(nullptr);
  }
  return mean;
}

Json diff_vs_paper(const Json& ours, const Json& paper) {
  Json d = Json::object();
  for (auto it = paper.begin(); it != paper.end(); ++it) {
    const std::string& k = it.key();
    const double p = it.value().get<double>();
    Json e{{"paper", p}};
    if (ours.contains(k) && ours[k].is_number()) {
      const double o = ours[k].get<double>();
      e["ours"] = o;
      e["diff"] = o - p;
      e["rel_diff"] = p != 0 ? Json((o - p) / std::fabs(p)) : Json(nullptr);
      const MetricInfo* info = metric_info(k);
      e["better"] = info ? Json(info->lower_better ? o < p : o > p) : Json(nullptr);
    } else {
      e["ours"] = nullptr;
      e["diff"] = nullptr;
      e["rel_diff"] = nullptr;
      e["better"] = nullptr;
    }
    d[k] = e;
  }
  return d;
}

Json row_timings(const std::vector<Json>& sequences) {
  std::map<std::string, std::vector<double>> reps;
  for (const auto& s : sequences) {
    const Json t = s.value("timings", Json::object());
    for (auto it = t.begin(); it != t.end(); ++it) {
      const auto r = repetitions(it.value());
      reps[it.key()].insert(reps[it.key()].end(), r.begin(), r.end());
    }
  }
  Json out = Json::object();
  for (const auto& [phase, v] : reps) out[phase] = summarize(v);
  return out;
}

Json make_row(const std::string& table, const RowDef& row, const std::string& status,
              const std::vector<Json>& sequences, const std::string& error,
              const std::vector<std::string>& real_sequences) {
  Json r;
  r["method"] = row.method;
  r["label"] = row.label;
  r["status"] = status;
  r["implemented"] = status != "not_implemented";
  r["error"] = error.empty() ? Json(nullptr) : Json(error);
  const Json paper = paper_numbers(table, row.method);
  r["paper"] = paper;
  r["paper_unverified"] = unverified_numbers(table, row.method);
  if (status == "ok") {
    std::vector<Json> twins, reals;
    for (const auto& s : sequences) {
      const std::string name = s.value("sequence", "");
      const bool is_real = std::find(real_sequences.begin(), real_sequences.end(), name) !=
                           real_sequences.end();
      (is_real ? reals : twins).push_back(s);
    }
    r["mean"] = mean_over_sequences(twins);
    if (!reals.empty()) r["mean_real"] = mean_over_sequences(reals);
    Json all_paper = paper;
    const Json unv = r["paper_unverified"];
    for (auto it = unv.begin(); it != unv.end(); ++it) all_paper[it.key()] = it.value();
    r["diff_vs_paper"] = diff_vs_paper(r["mean"], all_paper);
    r["timings"] = row_timings(sequences);
  } else {
    r["mean"] = nullptr;
    r["diff_vs_paper"] = nullptr;
    r["timings"] = Json::object();
  }
  r["sequences"] = sequences;
  return r;
}

}  // namespace sgnlf::harness
