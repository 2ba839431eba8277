// What a header needs to declare config and JSON functions without the full nlohmann/json
// (json_fwd only): the Json alias, ConfigReader declared, ConfigError, and the file and hash
// helpers. Files that read, write or build JSON include core/config.hpp.
#pragma once
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <set>
#include <string>

#include "core/error.hpp"

namespace sgnlf {

using Json = nlohmann::json;
class ConfigReader;

// The valid key nearest to `key` (edit distance at most max(2, |key| / 3)), or "" when none is.
std::string nearest_key(const std::string& key, const std::set<std::string>& valid);

// Loads a JSON file; errors name the file and the parser's byte position.
Json load_json_file(const std::string& path);
// A config file the user names (--config): like load_json_file, but a missing file or a syntax
// error is a ConfigError (exit 2 in apps/), naming the file and the line and column.
Json load_config_file(const std::string& path);
// Writes JSON atomically (temporary file + rename) with 2-space indentation.
void write_json_file(const std::string& path, const Json& j);
// Writes any text atomically (temporary file + rename).
void write_text_file(const std::string& path, const std::string& text);

// Range check helper for validate(): throws ConfigError naming the key and value.
template <typename T>
void check_range(const std::string& where, const std::string& key, T value, T lo, T hi) {
  if (!(value >= lo && value <= hi))
    throw ConfigError(where + ": '" + key + "' = " + std::to_string(value) + " outside [" +
                      std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

// 64-bit FNV-1a hash, used for config hashes and kernel source hashes.
uint64_t fnv1a64(const std::string& data, uint64_t h = 1469598103934665603ull);
std::string hex64(uint64_t v);

}  // namespace sgnlf
