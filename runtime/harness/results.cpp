#include "harness/results.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "core/config.hpp"
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
      e["better"] = info && info->judged() ? Json(info->lower_better ? o < p : o > p) : Json(nullptr);
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

SeedStats seed_stats(const std::vector<Json>& per_seed) {
  std::set<std::string> keys;
  for (const auto& m : per_seed)
    if (m.is_object())
      for (auto it = m.begin(); it != m.end(); ++it) keys.insert(it.key());
  SeedStats st;
  const double n = double(per_seed.size());
  for (const auto& k : keys) {
    std::vector<double> v;
    for (const auto& m : per_seed)
      if (m.is_object() && m.contains(k) && m[k].is_number()) v.push_back(m[k].get<double>());
    if (v.size() != per_seed.size() || v.empty()) {
      st.mean[k] = nullptr;
      st.sd[k] = nullptr;
      continue;
    }
    double sum = 0;
    for (double x : v) sum += x;
    const double mean = sum / n;
    st.mean[k] = mean;
    if (v.size() < 2) {
      st.sd[k] = nullptr;
      continue;
    }
    double ss = 0;
    for (double x : v) ss += (x - mean) * (x - mean);
    st.sd[k] = std::sqrt(ss / (n - 1));
  }
  return st;
}

Json seed_sequence_entry(const std::vector<Json>& runs) {
  require(!runs.empty(), "seed_sequence_entry: no runs");
  Json e;
  e["sequence"] = runs.front().value("sequence", "");
  Json seeds = Json::array(), hashes = Json::array();
  std::vector<Json> metrics, pose, all;
  for (const auto& r : runs) {
    seeds.push_back(r.value("seed", Json(nullptr)));
    hashes.push_back(r.value("config_hash", Json(nullptr)));
    metrics.push_back(r.value("metrics", Json::object()));
    pose.push_back(r.value("pose_metrics", Json()));
    all.push_back(all_metrics(r));
  }
  e["seeds"] = seeds;
  e["dataset"] = runs.front().value("dataset", Json());
  e["config_hash"] = config_hash(hashes);
  e["metrics"] = seed_stats(metrics).mean;
  e["pose_metrics"] = pose.front().is_object() ? seed_stats(pose).mean : Json(nullptr);
  e["metrics_sd"] = seed_stats(all).sd;
  e["timings"] = row_timings(runs);
  e["runs"] = runs;
  return e;
}

std::vector<uint64_t> entry_seeds(const Json& e) {
  std::vector<uint64_t> v;
  if (e.contains("runs") && e["runs"].is_array()) {
    for (const auto& r : e["runs"]) v.push_back(r.value("seed", uint64_t(1)));
    return v;
  }
  return {e.value("seed", uint64_t(1))};
}

namespace {

// Runs grouped by sequence, in order of first appearance; each sequence's runs in their order.
std::vector<std::pair<std::string, std::vector<Json>>> by_sequence(const std::vector<Json>& runs) {
  std::vector<std::pair<std::string, std::vector<Json>>> v;
  for (const auto& s : runs) {
    const std::string name = s.value("sequence", "");
    auto it = std::find_if(v.begin(), v.end(), [&](const auto& p) { return p.first == name; });
    if (it == v.end()) {
      v.push_back({name, {}});
      it = v.end() - 1;
    }
    it->second.push_back(s);
  }
  return v;
}

// One group's (the twins', or the real sequences') mean into r[key], and with several seeds its
// spread (results/schema.md "Several seeds"). Every sequence with the same seeds, two or more:
// per seed the mean over sequences, then mean and spread of those over the seeds. One run per
// sequence: the mean over sequences. Else (a combined table whose sequences have different
// seeds): the mean over sequences of each sequence's seed mean, and the spread over the seeds
// every sequence has, when they are two or more.
void group_mean(Json& r, const std::string& key,
                const std::vector<std::pair<std::string, std::vector<Json>>>& group) {
  std::vector<Json> flat, entries;
  std::vector<uint64_t> common;
  bool same = true;
  for (size_t i = 0; i < group.size(); ++i) {
    std::vector<uint64_t> seeds;
    for (const auto& run : group[i].second) {
      flat.push_back(run);
      seeds.push_back(run.value("seed", uint64_t(1)));
    }
    if (i == 0) {
      common = seeds;
    } else {
      same &= seeds == common;
      common.erase(std::remove_if(common.begin(), common.end(),
                                  [&](uint64_t s) {
                                    return std::find(seeds.begin(), seeds.end(), s) == seeds.end();
                                  }),
                   common.end());
    }
    entries.push_back(group[i].second.size() > 1 ? seed_sequence_entry(group[i].second)
                                                 : group[i].second.front());
  }
  if (common.size() < 2) {  // one run per sequence, or fewer than two seeds shared by all
    r[key] = mean_over_sequences(entries);
    return;
  }
  std::vector<Json> means;
  Json list = Json::array();
  for (const uint64_t seed : common) {
    std::vector<Json> of_seed;
    for (const auto& s : flat)
      if (s.value("seed", Json()) == Json(seed)) of_seed.push_back(s);
    means.push_back(mean_over_sequences(of_seed));
    list.push_back(Json{{"seed", seed}, {"mean", means.back()}});
  }
  const SeedStats st = seed_stats(means);
  r[key] = same ? st.mean : mean_over_sequences(entries);
  r[key + "_sd"] = st.sd;
  r[key + "_by_seed"] = list;
}

}  // namespace

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
  if (status != "ok") {
    r["mean"] = nullptr;
    r["diff_vs_paper"] = nullptr;
    r["timings"] = Json::object();
    r["sequences"] = sequences;
    return r;
  }
  const auto groups = by_sequence(sequences);
  std::vector<std::pair<std::string, std::vector<Json>>> twins, reals;
  for (const auto& g : groups)
    (std::find(real_sequences.begin(), real_sequences.end(), g.first) != real_sequences.end() ? reals
                                                                                                : twins)
        .push_back(g);
  group_mean(r, "mean", twins);
  if (!reals.empty()) group_mean(r, "mean_real", reals);
  Json all_paper = paper;
  const Json unv = r["paper_unverified"];
  for (auto it = unv.begin(); it != unv.end(); ++it) all_paper[it.key()] = it.value();
  r["diff_vs_paper"] = diff_vs_paper(r["mean"], all_paper);
  r["timings"] = row_timings(sequences);
  // One entry per sequence: a run alone as it is; several seeds' runs as their mean, spread and
  // runs (seed_sequence_entry).
  Json entries = Json::array();
  for (const auto& g : groups)
    entries.push_back(g.second.size() > 1 ? seed_sequence_entry(g.second) : g.second.front());
  r["sequences"] = entries;
  return r;
}

}  // namespace sgnlf::harness
