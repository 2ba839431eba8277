// Checkpoint file format (little-endian):
//   "SGNLFCK1" | u32 version | i64 step | u64 seed | u64 config_hash | f64 best_loss |
//   f64 smoothed_loss | u32 n_arrays | n × (u32 name_len, name, u64 count, count × f32) |
//   u64 FNV-1a of everything before it.
#include "pipeline/checkpoint.hpp"

#include <cstring>
#include <fstream>
#include <iterator>

#include "core/config.hpp"
#include "core/error.hpp"

namespace sgnlf::pipeline {
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
    if (pos_ + n > d_.size())
      throw IoError(path_ + ": truncated checkpoint (reading " + what + " at byte " +
                    std::to_string(pos_) + ")");
  }
  const std::string& d_;
  const std::string& path_;
  size_t pos_ = 0;
};

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
  write_text_file(path, out);  // atomic: temporary file + rename
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

std::vector<float> pack_doubles(const std::vector<double>& v) {
  std::vector<float> out(2 * v.size());
  std::memcpy(out.data(), v.data(), v.size() * sizeof(double));
  return out;
}

std::vector<double> unpack_doubles(const std::vector<float>& v) {
  std::vector<double> out(v.size() / 2);
  std::memcpy(out.data(), v.data(), out.size() * sizeof(double));
  return out;
}

}  // namespace sgnlf::pipeline
