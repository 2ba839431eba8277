// Preparing a table's sequence on disk for the pipeline (built only when the datasets module
// is wired in): a synthetic twin is simulated and written in the synthetic layout; a real
// window (--data-root, or <real root>/<real_dir> for a real sequence of a synthetic scale:
// sequence_data_root()) is loaded from its own layout and written out in the same synthetic
// layout, so the pipeline always reads one folder holding exactly the protocol window.
#pragma once
#include <string>

#include "harness/runner.hpp"

namespace sgnlf::harness {

// Seed of the simulated worlds: fixed, so --seed changes training only and every run of a
// table sees the same data.
constexpr uint64_t kSyntheticDataSeed = 1;

PreparedSequence prepare_sequence(const SequenceDef& s, const BenchOptions& opt,
                                  const std::string& dir);

}  // namespace sgnlf::harness
