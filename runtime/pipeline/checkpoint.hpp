// Training checkpoints: named float arrays (parameters, Adam moments, ...), the step, the seed
// and the config hash, in one binary file written atomically (temporary file + rename) and
// validated on load (magic, version, sizes, checksum, config hash) with errors naming the file.
// Ray batches and jitter are keyed by (seed, step), so the RNG position is the step itself and
// resuming from a checkpoint reproduces the uninterrupted run bit for bit.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace sgnlf::pipeline {

struct Checkpoint {
  long step = 0;                 // completed iterations
  uint64_t seed = 0;
  uint64_t config_hash = 0;
  double best_loss = 0.0;        // divergence tracker state (smoothed loss minimum)
  double smoothed_loss = 0.0;
  std::vector<std::pair<std::string, std::vector<float>>> arrays;

  // The array called `name`; IoError when absent or not of `expected_size` (if > 0).
  const std::vector<float>& array(const std::string& name, size_t expected_size = 0) const;
};

// Doubles stored bit-exactly in a float array (two slots each), for host state such as poses
// whose resumed run must be bit-identical.
std::vector<float> pack_doubles(const std::vector<double>& v);
std::vector<double> unpack_doubles(const std::vector<float>& v);

void save_checkpoint(const std::string& path, const Checkpoint& ck);
// Throws IoError (naming the file and what is wrong) for missing, truncated or corrupt files.
Checkpoint load_checkpoint(const std::string& path);
// As load_checkpoint, and also refuses a checkpoint written under another config or seed.
Checkpoint load_checkpoint_for(const std::string& path, uint64_t config_hash, uint64_t seed);

}  // namespace sgnlf::pipeline
