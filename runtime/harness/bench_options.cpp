#include "harness/bench_options.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/config.hpp"

namespace sgnlf::harness {
namespace fs = std::filesystem;

void BenchOptions::validate() const {
  table_def(table);  // throws for an unknown table
  const auto scales = scale_names();
  if (std::find(scales.begin(), scales.end(), scale) == scales.end())
    throw ConfigError("bench: unknown scale '" + scale + "' (known: smoke, quick, paper)");
  if (out_dir.empty()) throw ConfigError("bench: --out is required");
  for (size_t i = 0; i < seeds.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (seeds[i] == seeds[j])
        throw ConfigError("bench: --seeds: seed " + std::to_string(seeds[i]) +
                          " is listed twice");
  if (!data_root.empty() && !fs::is_directory(data_root))
    throw ConfigError("bench: --data-root '" + data_root + "' is not a directory");
  if (!real_root.empty() && !fs::is_directory(real_root))
    throw ConfigError("bench: --real-root '" + real_root + "' is not a directory");
  const TableDef t = table_def(table);
  for (const auto& r : rows) {
    const bool known = std::any_of(t.rows.begin(), t.rows.end(),
                                   [&](const RowDef& d) { return d.method == r; });
    if (!known) throw ConfigError("bench: --rows: table " + table + " has no row '" + r + "'");
  }
  const auto seqs = table_sequences(t, scale, !data_root.empty());
  for (const auto& q : sequences) {
    const bool known = std::any_of(seqs.begin(), seqs.end(),
                                   [&](const SequenceDef& d) { return d.name == q; });
    if (!known)
      throw ConfigError("bench: --sequences: table " + table + " at scale " + scale +
                        " has no sequence '" + q + "'");
    // A real sequence chosen by name must be there: an error, not a silent skip.
    for (const auto& d : seqs)
      if (d.name == q && d.is_real_dir() && data_root.empty() &&
          !fs::is_directory(sequence_data_root(d, *this)))
        throw ConfigError("bench: --sequences " + q + ": real data not found at " +
                          sequence_data_root(d, *this) +
                          " (--real-root DIR, or $SGNLF_SHARED_DIR/data/real)");
  }
}

std::string BenchOptions::resolved_real_root() const {
  return real_root.empty() ? default_real_root() : real_root;
}

std::string default_real_root() {
  const char* env = std::getenv("SGNLF_SHARED_DIR");
  if (env && *env) return (fs::path(env) / "data" / "real").string();
  return (fs::path("..") / "shared" / "data" / "real").string();
}

std::string sequence_data_root(const SequenceDef& s, const BenchOptions& opt) {
  if (!opt.data_root.empty()) return opt.data_root;
  if (s.is_real_dir()) return (fs::path(opt.resolved_real_root()) / s.real_dir).string();
  return "";
}

std::vector<uint64_t> BenchOptions::seed_list() const {
  return seeds.empty() ? std::vector<uint64_t>{seed} : seeds;
}

Json BenchOptions::to_json() const {
  Json j{{"table", table},   {"scale", scale}, {"data_root", data_root},
         {"device", device}, {"seed", seed},   {"roofline", roofline}};
  const auto sl = seed_list();
  if (sl.size() > 1) {  // several seeds: `seeds` instead of `seed` (one seed: unchanged)
    j.erase("seed");
    j["seeds"] = sl;
  } else {
    j["seed"] = sl.front();
  }
  if (!device_profile.empty()) j["device_profile"] = device_profile;
  if (!rows.empty()) j["rows"] = rows;
  if (!sequences.empty()) j["sequences"] = sequences;
  return j;
}

}  // namespace sgnlf::harness
