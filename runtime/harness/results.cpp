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

Json make_row(const std::string& table, const RowDef& row, const std::string& status,
              const std::vector<Json>& sequences, const std::string& error,
              const std::vector<std::string>& real_sequences, const std::vector<uint64_t>& seeds) {
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
    if (seeds.size() > 1) {
      // Per seed, the mean over sequences; then mean and spread of those over the seeds.
      const auto by_seed = [&](const std::vector<Json>& group, const char* key) {
        std::vector<Json> means;
        Json list = Json::array();
        for (const uint64_t seed : seeds) {
          std::vector<Json> of_seed;
          for (const auto& s : group)
            if (s.value("seed", Json()) == Json(seed)) of_seed.push_back(s);
          means.push_back(mean_over_sequences(of_seed));
          list.push_back(Json{{"seed", seed}, {"mean", means.back()}});
        }
        const SeedStats st = seed_stats(means);
        r[key] = st.mean;
        r[std::string(key) + "_sd"] = st.sd;
        r[std::string(key) + "_by_seed"] = list;
      };
      by_seed(twins, "mean");
      if (!reals.empty()) by_seed(reals, "mean_real");
    } else {
      r["mean"] = mean_over_sequences(twins);
      if (!reals.empty()) r["mean_real"] = mean_over_sequences(reals);
    }
    Json all_paper = paper;
    const Json unv = r["paper_unverified"];
    for (auto it = unv.begin(); it != unv.end(); ++it) all_paper[it.key()] = it.value();
    r["diff_vs_paper"] = diff_vs_paper(r["mean"], all_paper);
    r["timings"] = row_timings(sequences);
    if (seeds.size() > 1) {  // one entry per sequence: its seeds' runs, mean and spread
      std::vector<std::string> order;
      std::map<std::string, std::vector<Json>> of_seq;
      for (const auto& s : sequences) {
        const std::string name = s.value("sequence", "");
        if (!of_seq.count(name)) order.push_back(name);
        of_seq[name].push_back(s);
      }
      Json agg = Json::array();
      for (const auto& name : order) agg.push_back(seed_sequence_entry(of_seq[name]));
      r["sequences"] = agg;
      return r;
    }
  } else {
    r["mean"] = nullptr;
    r["diff_vs_paper"] = nullptr;
    r["timings"] = Json::object();
  }
  r["sequences"] = sequences;
  return r;
}

}  // namespace sgnlf::harness
