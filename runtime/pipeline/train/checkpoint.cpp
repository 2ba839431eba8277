// Checkpoint file format (little-endian):
//   "SGNLFCK1" | u32 version | i64 step | u64 seed | u64 config_hash | f64 best_loss |
//   f64 smoothed_loss | u32 n_arrays | n × (u32 name_len, name, u64 count, count × f32) |
//   u64 FNV-1a of everything before it.
#include "pipeline/train/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/config.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace sgnlf::pipeline {
namespace fs = std::filesystem;
namespace {

constexpr char kMagic[8] = {'S', 'G', 'N', 'L', 'F', 'C', 'K', '1'};
constexpr uint32_t kVersion = 1;

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

class Reader {
 public:
  Reader(const std::string& data, const std::string& path) : d_(data), path_(path) {}
  template <typename T>
  T get(const char* what) {
    T v;
    need(sizeof(T), what);
    std::memcpy(&v, d_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }
  void bytes(void* dst, size_t n, const char* what) {
    need(n, what);
    if (n) std::memcpy(dst, d_.data() + pos_, n);
    pos_ += n;
  }
  size_t pos() const { return pos_; }

 private:
  void need(size_t n, const char* what) {
    if (n > d_.size() - pos_)
      throw IoError(path_ + ": truncated checkpoint (reading " + what + " at byte " +
                    std::to_string(pos_) + ")");
  }
  const std::string& d_;
  const std::string& path_;
  size_t pos_ = 0;
};

// Writes `data` to `file` and syncs it to disk. On failure `file` is removed and the error names
// `path` (the file the caller is producing) and the system's reason (ENOSPC, EACCES, EFBIG...).
void write_synced(const std::string& file, const std::string& data, const std::string& path,
                  long fault_step = -1) {
  auto fail = [&](const std::string& what, int fd) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    ::unlink(file.c_str());
    throw IoError(path + ": " + what + " (" + why + "); an existing " +
                  fs::path(path).filename().string() + " is left as it was");
  };
  std::error_code ec;
  const fs::path parent = fs::path(file).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) throw IoError(path + ": cannot create the folder " + parent.string() + " (" + ec.message() + ")");
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail("cannot open " + file + " for writing", -1);
  // Under fault injection only: the first half, synced, then the "checkpoint-partial" point.
  const bool split = fault_step >= 0 && std::getenv("SGNLF_FAULT_KILL") != nullptr;
  size_t done = 0;
  while (done < data.size()) {
    const size_t chunk = split && done == 0 ? data.size() / 2 : data.size() - done;
    const ssize_t n = ::write(fd, data.data() + done, chunk);
    if (split && done == 0 && n > 0) {
      ::fsync(fd);
      fault_point("checkpoint-partial", fault_step);
    }
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      fail("write failed after " + std::to_string(done) + " of " + std::to_string(data.size()) +
               " bytes of " + file,
           fd);
    }
    done += size_t(n);
  }
  if (::fsync(fd) != 0) fail("fsync of " + file + " failed", fd);
  if (::close(fd) != 0) fail("close of " + file + " failed", -1);
}

void rename_or_throw(const std::string& from, const std::string& to, const std::string& note) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(from.c_str());
    throw IoError(to + ": cannot rename from " + from + " (" + why + ")" + note);
  }
}

// The file format above, checksum included.
std::string serialize(const Checkpoint& ck) {
  std::string out(kMagic, sizeof kMagic);
  put(out, kVersion);
  put(out, int64_t(ck.step));
  put(out, ck.seed);
  put(out, ck.config_hash);
  put(out, ck.best_loss);
  put(out, ck.smoothed_loss);
  put(out, uint32_t(ck.arrays.size()));
  for (const auto& [name, v] : ck.arrays) {
    put(out, uint32_t(name.size()));
    out += name;
    put(out, uint64_t(v.size()));
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(float));
  }
  put(out, fnv1a64(out));
  return out;
}

}  // namespace

const std::vector<float>& Checkpoint::array(const std::string& name, size_t expected) const {
  for (const auto& [n, v] : arrays) {
    if (n != name) continue;
    if (expected > 0 && v.size() != expected)
      throw IoError("checkpoint array '" + name + "' has " + std::to_string(v.size()) +
                    " values, expected " + std::to_string(expected));
    return v;
  }
  throw IoError("checkpoint has no array '" + name + "'");
}

void save_checkpoint(const std::string& path, const Checkpoint& ck) {
  const std::string tmp = path + ".tmp";
  write_synced(tmp, serialize(ck), path);
  rename_or_throw(tmp, path, "");
}

std::string previous_checkpoint_path(const std::string& latest_path) {
  return (fs::path(latest_path).parent_path() / "previous.ckpt").string();
}

void save_checkpoint_rotating(const std::string& latest_path, const Checkpoint& ck) {
  // 1. the new state complete and synced in latest.ckpt.tmp; 2. previous.ckpt replaced by a
  // hard link to the current latest (through previous.ckpt.tmp, an atomic rename); 3. the new
  // state renamed over latest. latest.ckpt is never absent, and a kill at any point leaves
  // latest (old or new) and previous complete.
  const std::string prev = previous_checkpoint_path(latest_path);
  const std::string tmp = latest_path + ".tmp";
  write_synced(tmp, serialize(ck), latest_path, ck.step);
  fault_point("checkpoint-written", ck.step);
  std::error_code ec;
  if (fs::exists(latest_path, ec)) {
    const std::string prev_tmp = prev + ".tmp";
    fs::remove(prev_tmp, ec);
    fs::create_hard_link(latest_path, prev_tmp, ec);
    if (ec) {  // a file system without hard links: a copy
      ec.clear();
      fs::copy_file(latest_path, prev_tmp, fs::copy_options::overwrite_existing, ec);
    }
    if (ec) {
      fs::remove(tmp, ec);
      throw IoError(latest_path + ": cannot keep it as " + prev + " (" + ec.message() +
                    "); latest.ckpt is left as it was");
    }
    rename_or_throw(prev_tmp, prev, "; latest.ckpt is left as it was");
    fault_point("checkpoint-linked", ck.step);
  }
  rename_or_throw(tmp, latest_path, "; the previous checkpoint is kept at " + prev);
}

bool have_checkpoint(const std::string& latest_path) {
  std::error_code ec;
  return fs::exists(latest_path, ec) || fs::exists(previous_checkpoint_path(latest_path), ec);
}

Checkpoint load_latest_checkpoint(const std::string& latest_path, uint64_t config_hash,
                                  uint64_t seed, std::string* used) {
  const std::string prev = previous_checkpoint_path(latest_path);
  std::string latest_problem;
  try {
    Checkpoint ck = load_checkpoint_for(latest_path, config_hash, seed);
    if (used) *used = latest_path;
    return ck;
  } catch (const IoError& e) {
    latest_problem = e.what();
  }
  std::error_code ec;
  if (!fs::exists(prev, ec))
    throw IoError(latest_problem + "; no earlier checkpoint (" + prev + ") to fall back to");
  log::warn(latest_problem, "; falling back to ", prev);
  try {
    Checkpoint ck = load_checkpoint_for(prev, config_hash, seed);
    if (used) *used = prev;
    return ck;
  } catch (const IoError& e) {
    throw IoError(latest_problem + "; the fallback " + e.what());
  }
}

Checkpoint load_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open checkpoint");
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (data.size() < sizeof kMagic + 8 || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
    throw IoError(path + ": not an sgnlf checkpoint (bad magic)");
  uint64_t stored = 0;
  std::memcpy(&stored, data.data() + data.size() - 8, 8);
  if (fnv1a64(data.substr(0, data.size() - 8)) != stored)
    throw IoError(path + ": checkpoint checksum mismatch (corrupt or truncated file)");
  const std::string body = data.substr(0, data.size() - 8);
  Reader r(body, path);
  char magic[8];
  r.bytes(magic, 8, "magic");
  const auto version = r.get<uint32_t>("version");
  if (version != kVersion)
    throw IoError(path + ": checkpoint version " + std::to_string(version) + ", expected " +
                  std::to_string(kVersion));
  Checkpoint ck;
  ck.step = long(r.get<int64_t>("step"));
  ck.seed = r.get<uint64_t>("seed");
  ck.config_hash = r.get<uint64_t>("config hash");
  ck.best_loss = r.get<double>("best loss");
  ck.smoothed_loss = r.get<double>("smoothed loss");
  const auto n = r.get<uint32_t>("array count");
  for (uint32_t i = 0; i < n; ++i) {
    const auto len = r.get<uint32_t>("array name length");
    if (len > body.size() - r.pos())  // before allocating: a corrupt length could ask for 4 GB
      throw IoError(path + ": array name length " + std::to_string(len) + " at byte " +
                    std::to_string(r.pos()) + " is more than the file holds");
    std::string name(len, '\0');
    r.bytes(name.data(), len, "array name");
    const auto count = r.get<uint64_t>("array size");
    if (count > (body.size() - r.pos()) / sizeof(float))
      throw IoError(path + ": array '" + name + "' claims " + std::to_string(count) +
                    " values, more than the file holds");
    std::vector<float> v(count);
    r.bytes(v.data(), count * sizeof(float), "array values");
    ck.arrays.emplace_back(std::move(name), std::move(v));
  }
  if (r.pos() != body.size()) throw IoError(path + ": trailing bytes after the last array");
  return ck;
}

Checkpoint load_checkpoint_for(const std::string& path, uint64_t config_hash, uint64_t seed) {
  Checkpoint ck = load_checkpoint(path);
  if (ck.config_hash != config_hash)
    throw ConfigError(path + ": checkpoint was written under config " + hex64(ck.config_hash) +
                      ", the run's config is " + hex64(config_hash) +
                      " (resume needs the same resolved config)");
  if (ck.seed != seed)
    throw ConfigError(path + ": checkpoint seed " + std::to_string(ck.seed) +
                      " differs from the run's seed " + std::to_string(seed));
  return ck;
}

void fault_point(const char* point, long step) {
  const char* env = std::getenv("SGNLF_FAULT_KILL");
  if (!env || !*env) return;
  if (std::string(env) != std::string(point) + "@" + std::to_string(step)) return;
  std::fprintf(stderr, "SGNLF_FAULT_KILL: killing the process at %s@%ld\n", point, step);
  std::fflush(stderr);
  ::raise(SIGKILL);
}

std::vector<float> pack_doubles(const std::vector<double>& v) {
  std::vector<float> out(2 * v.size());
  // An empty vector's data() may be null, and memcpy from null is undefined even for 0 bytes
  // (UBSan found it: a pose graph without edges, tests/pipeline/test_sgnlf.cpp).
  if (!v.empty()) std::memcpy(out.data(), v.data(), v.size() * sizeof(double));
  return out;
}

std::vector<double> unpack_doubles(const std::vector<float>& v) {
  std::vector<double> out(v.size() / 2);
  if (!out.empty()) std::memcpy(out.data(), v.data(), out.size() * sizeof(double));
  return out;
}

}  // namespace sgnlf::pipeline
