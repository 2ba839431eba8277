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
// The rotating pair of a run folder: <dir>/latest.ckpt and, one checkpoint older,
// <dir>/previous.ckpt, so that a latest.ckpt damaged after it was written (a disk error, a
// copy cut short) still leaves a state to resume from.
std::string previous_checkpoint_path(const std::string& latest_path);
// Writes `ck` as the new latest, keeping the old latest as previous (save_checkpoint's
// guarantees; killed at any point, at least one of the two files holds a complete checkpoint).
void save_checkpoint_rotating(const std::string& latest_path, const Checkpoint& ck);
// True when latest or previous exists.
bool have_checkpoint(const std::string& latest_path);
// Loads latest; when it is missing or corrupt (IoError), warns and falls back to previous.
// ConfigError (another config or seed) is not a reason to fall back. Throws IoError naming both
// files when neither loads. `used` (optional) receives the path that was loaded.
Checkpoint load_latest_checkpoint(const std::string& latest_path, uint64_t config_hash,
                                  uint64_t seed, std::string* used = nullptr);

// Fault injection for the crash-safety tests: when the environment variable SGNLF_FAULT_KILL
// is "<point>@<step>" and matches, the process kills itself with SIGKILL (no cleanup, no
// destructors: what a power cut or the OOM killer does to the process). Points:
//   after-step          the trainer, right after step <step> (before its checkpoint, if due)
//   checkpoint-partial  save_checkpoint_rotating, half of latest.ckpt.tmp written
//   checkpoint-written  latest.ckpt.tmp complete and synced, nothing renamed yet
//   checkpoint-linked   previous.ckpt replaced by the old latest, the new one not yet renamed
// Unset (always, outside those tests) it costs one getenv per call.
void fault_point(const char* point, long step);

std::vector<float> pack_doubles(const std::vector<double>& v);
std::vector<double> unpack_doubles(const std::vector<float>& v);

// Atomic and durable: written to `path`.tmp, flushed to disk (fsync), then renamed over `path`.
// A failed write (unwritable folder, full disk) throws IoError naming the file and the system's
// reason, removes the temporary file and leaves an existing `path` untouched.
void save_checkpoint(const std::string& path, const Checkpoint& ck);
// Throws IoError (naming the file and what is wrong) for missing, truncated or corrupt files.
Checkpoint load_checkpoint(const std::string& path);
// As load_checkpoint, and also refuses a checkpoint written under another config or seed.
Checkpoint load_checkpoint_for(const std::string& path, uint64_t config_hash, uint64_t seed);

}  // namespace sgnlf::pipeline
