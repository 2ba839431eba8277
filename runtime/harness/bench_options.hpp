// `sgnlf bench`'s options: which table, scale, seeds, rows and sequences, and where the
// data is read from.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/config_fwd.hpp"
#include "harness/tables.hpp"

namespace sgnlf::harness {

struct BenchOptions {
  std::string table;
  std::string scale = "smoke";
  std::string data_root;  // "" = built-in synthetic twins
  // Folder holding real datasets for the sequences of a synthetic scale that set `real_dir`
  // (SequenceDef); "" = default_real_root(). Such a sequence is read from
  // <real_root>/<real_dir> when that folder exists and skipped (recorded) otherwise. Not part
  // of to_json() (a machine's path; the twins' numbers do not depend on it): results record it
  // at the top level (`real_root`, results/schema.md).
  std::string real_root;
  std::string out_dir;
  std::string device;     // OpenCL device spec ("" = default)
  // Device profile spec (cl/device_profile.hpp; "" = SGNLF_DEVICE_PROFILE or automatic). In
  // to_json() only when set, so a table's config_hash does not change; the profile in force is
  // recorded in the context.
  std::string device_profile;
  uint64_t seed = 1;
  // --seeds: every cell runs with each of these (results/schema.md "Several seeds"); empty =
  // the one `seed`. One element is the same as --seed (a single-seed result, unchanged).
  std::vector<uint64_t> seeds;
  bool roofline = true;   // measure and record the device's roofline
  std::string command;    // the command line, recorded verbatim
  // Subsets (empty = all): rows outside `rows` are kept in the result as status "skipped";
  // `sequences` narrows the scale's sequences (means are over the ones run). Recorded in the
  // config only when non-empty, so a full table's config_hash does not change.
  std::vector<std::string> rows, sequences;
  void validate() const;
  std::vector<uint64_t> seed_list() const;  // `seeds`, or {seed} when empty
  Json to_json() const;   // the resolved harness config (without `command`, `out_dir`, `real_root`)
  std::string resolved_real_root() const;  // real_root, or default_real_root() when empty
};

// $SGNLF_SHARED_DIR/data/real when that variable is set, else "../shared/data/real" (relative
// to the working directory: the shared folder beside a checkout run from its root).
std::string default_real_root();

// The folder a sequence's data is read from in its own layout: --data-root for the real
// windows, <resolved_real_root()>/<real_dir> for a real sequence of a synthetic scale, ""
// for a synthetic twin (simulated).
std::string sequence_data_root(const SequenceDef& s, const BenchOptions& opt);

}  // namespace sgnlf::harness
