#include "core/config.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <vector>
#include <sstream>

namespace sgnlf {

ConfigReader::ConfigReader(const Json& j, std::string where) : j_(j), where_(std::move(where)) {
  if (!j_.is_object()) throw ConfigError(where_ + ": expected a JSON object, got " + j_.dump());
}

ConfigReader ConfigReader::child(const std::string& key) {
  asked_.insert(key);
  if (!j_.contains(key)) {
    static const Json empty = Json::object();
    return ConfigReader(empty, where_ + "." + key);
  }
  used_.insert(key);
  return ConfigReader(j_.at(key), where_ + "." + key);
}

std::string nearest_key(const std::string& key, const std::set<std::string>& valid) {
  std::string best;
  size_t best_d = std::max<size_t>(2, key.size() / 3) + 1;
  for (const auto& v : valid) {  // Levenshtein distance, one row at a time
    std::vector<size_t> row(v.size() + 1);
    for (size_t j = 0; j <= v.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= key.size(); ++i) {
      size_t diag = row[0];
      row[0] = i;
      for (size_t j = 1; j <= v.size(); ++j) {
        const size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (key[i - 1] == v[j - 1] ? 0 : 1)});
        diag = up;
      }
    }
    if (row[v.size()] < best_d) {
      best_d = row[v.size()];
      best = v;
    }
  }
  return best;
}

void ConfigReader::finish() const {
  std::string unknown;
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (used_.count(it.key())) continue;
    unknown += (unknown.empty() ? "'" : ", '") + it.key() + "'";
    const std::string near = nearest_key(it.key(), asked_);
    if (!near.empty() && !j_.contains(near)) unknown += " (did you mean '" + near + "'?)";
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

Json load_config_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open the config file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    size_t line = 1, col = 1;
    for (size_t k = 0; k + 1 < e.byte && k < text.size(); ++k) {
      if (text[k] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw ConfigError(path + ": invalid JSON at line " + std::to_string(line) + ", column " +
                      std::to_string(col) + ": " + e.what());
  } catch (const Json::exception& e) {
    throw ConfigError(path + ": invalid JSON: " + e.what());
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
