// Assembling the results JSON (results/schema.md): one entry per (row, sequence) run, rows
// averaged over sequences, the paper's numbers and our differences, timing summaries.
#pragma once
#include <string>
#include <vector>

#include "core/config.hpp"
#include "harness/tables.hpp"
#include "pipeline/run/method.hpp"

namespace sgnlf::harness {

// Hash of a resolved config: FNV-1a 64 of its compact dump (keys sorted), as 16 hex digits.
std::string config_hash(const Json& config);

// One run's entry in rows[].sequences[].
Json sequence_entry(const std::string& sequence, uint64_t seed, const Json& dataset,
                    const pipeline::MethodResult& r, const std::string& run_dir, double wall_s);

// Mean over sequences of every metric (metrics and pose_metrics); a metric that is null or
// missing in any sequence is null. Keys are the union over sequences.
Json mean_over_sequences(const std::vector<Json>& sequences);

// {metric: {ours, paper, diff, rel_diff, better}} for every metric the paper reports.
Json diff_vs_paper(const Json& ours, const Json& paper);

// {phase: summary} where each phase's repetitions are gathered over the sequences.
Json row_timings(const std::vector<Json>& sequences);

// A complete row: status "ok" | "not_implemented" | "failed" | "skipped". `sequences` holds
// one-seed run entries (sequence_entry), a sequence's seeds in the order to report them.
// `real_sequences` names the real sequences of a synthetic scale (SequenceDef::real_dir): they
// are averaged apart, in `mean_real` (present only when one of them ran), and `mean` and
// `diff_vs_paper` stay over the synthetic twins alone. A sequence with one run keeps it as its
// entry; one with several seeds' runs gets a several-seed entry (seed_sequence_entry). The
// means follow results/schema.md "Several seeds": with every sequence of the group on the same
// two or more seeds, per seed the mean over sequences, then their mean (`mean`), sample sd
// (`mean_sd`) and list (`mean_by_seed`); with the sequences on different seeds, the mean over
// sequences of each sequence's seed mean, and the sd and list over the seeds every sequence
// has, when those are two or more.
Json make_row(const std::string& table, const RowDef& row, const std::string& status,
              const std::vector<Json>& sequences, const std::string& error = "",
              const std::vector<std::string>& real_sequences = {});

// The seeds of a run entry: a several-seed entry's runs' seeds, else its own `seed` (1 when
// absent, as in results made before seeds were recorded).
std::vector<uint64_t> entry_seeds(const Json& entry);

// Several seeds (results/schema.md "Several seeds"): per metric the mean and the sample
// standard deviation (n − 1) over the objects given (one per seed); a metric null or missing
// in any of them is null in both, and the deviation is null for fewer than 2.
struct SeedStats {
  Json mean = Json::object(), sd = Json::object();
};
SeedStats seed_stats(const std::vector<Json>& per_seed);

// One sequence's entry of a several-seed row: the seeds' runs (`runs`, each a one-seed entry)
// and their mean (`metrics`, `pose_metrics`) and spread (`metrics_sd`).
Json seed_sequence_entry(const std::vector<Json>& runs);

}  // namespace sgnlf::harness
