#include "core/config.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace sgnlf {

ConfigReader::ConfigReader(const Json& j, std::string where) : j_(j), where_(std::move(where)) {
  if (!j_.is_object()) throw ConfigError(where_ + ": expected a JSON object, got " + j_.dump());
}

ConfigReader ConfigReader::child(const std::string& key) {
  if (!j_.contains(key)) {
    static const Json empty = Json::object();
    return ConfigReader(empty, where_ + "." + key);
  }
  used_.insert(key);
  return ConfigReader(j_.at(key), where_ + "." + key);
}

void ConfigReader::finish() const {
  std::string unknown;
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (!used_.count(it.key())) unknown += (unknown.empty() ? "'" : ", '") + it.key() + "'";
  }
  if (!unknown.empty()) throw ConfigError(where_ + ": unknown key(s) " + unknown);
}

Json load_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw IoError(path + ": cannot open file");
  try {
    return Json::parse(in);
  } catch (const Json::parse_error& e) {
    throw IoError(path + ": invalid JSON at byte " + std::to_string(e.byte) + ": " + e.what());
  } catch (const Json::exception& e) {  // e.g. out_of_range 406: a number like 1e999 (fuzz_compare_results)
    throw IoError(path + ": invalid JSON: " + e.what());
  }
}

void write_text_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(tmp + ": cannot open for writing");
    out << text;
    out.flush();
    if (!out) throw IoError(tmp + ": write failed");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw IoError(path + ": cannot rename from " + tmp);
}

void write_json_file(const std::string& path, const Json& j) { write_text_file(path, j.dump(2) + "\n"); }

uint64_t fnv1a64(const std::string& data, uint64_t h) {
  for (unsigned char c : data) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string hex64(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace sgnlf
