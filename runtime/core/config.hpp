// Strict JSON configuration reading: every key a struct reads is marked as used, and finish()
// rejects the keys nobody read, naming them and the config they came from. This header brings
// the full nlohmann/json; a header that only names Json or ConfigReader includes
// core/config_fwd.hpp instead.
#pragma once
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "core/config_fwd.hpp"
#include "core/error.hpp"

namespace sgnlf {

namespace detail {
template <typename T>
struct IsScalarList : std::false_type {};
template <typename E, typename A>
struct IsScalarList<std::vector<E, A>>
    : std::bool_constant<std::is_arithmetic_v<E> || std::is_same_v<E, std::string>> {};
}  // namespace detail

class ConfigReader {
 public:
  // `where` names the source in errors, e.g. "configs/train.json: field".
  ConfigReader(const Json& j, std::string where);

  // Reads `key` into `out` when present (keeps the default otherwise).
  template <typename T>
  ConfigReader& get(const std::string& key, T& out) {
    asked_.insert(key);
    if (!j_.contains(key)) return *this;
    used_.insert(key);
    convert(key, j_.at(key), out);
    return *this;
  }
  // Reads `key`, which must be present.
  template <typename T>
  ConfigReader& require(const std::string& key, T& out) {
    if (!j_.contains(key)) throw ConfigError(where_ + ": missing required key '" + key + "'");
    return get(key, out);
  }
  // A nested object: returns a reader for it (marked used); the caller must finish() it.
  ConfigReader child(const std::string& key);
  bool has(const std::string& key) const {
    asked_.insert(key);
    return j_.contains(key);
  }
  // Throws ConfigError listing every key that was not read, each with the nearest key that
  // would have been read here when one is close (a misspelling).
  void finish() const;
  const std::string& where() const { return where_; }

 private:
  template <typename T>
  void convert(const std::string& key, const Json& v, T& out) {
    try {
      if constexpr (std::is_same_v<T, bool>) {
        if (!v.is_boolean()) throw ConfigError("");
        out = v.get<bool>();
      } else if constexpr (std::is_integral_v<T>) {
        // Out-of-range values are refused, never narrowed (e.g. 2^32 into an int).
        if (!v.is_number_integer()) throw ConfigError("");
        if constexpr (std::is_unsigned_v<T>) {
          if (!v.is_number_unsigned() && v.get<long long>() < 0) throw ConfigError("");
          const auto x = v.get<unsigned long long>();
          if (x > static_cast<unsigned long long>(std::numeric_limits<T>::max()))
            throw ConfigError("");
          out = static_cast<T>(x);
        } else {
          if (v.is_number_unsigned() &&
              v.get<unsigned long long>() > static_cast<unsigned long long>(
                                                std::numeric_limits<long long>::max()))
            throw ConfigError("");
          const auto x = v.get<long long>();
          if (x < static_cast<long long>(std::numeric_limits<T>::min()) ||
              x > static_cast<long long>(std::numeric_limits<T>::max()))
            throw ConfigError("");
          out = static_cast<T>(x);
        }
      } else if constexpr (std::is_floating_point_v<T>) {
        if (!v.is_number()) throw ConfigError("");
        out = v.get<T>();
        if (!std::isfinite(out)) throw ConfigError("");
      } else if constexpr (detail::IsScalarList<T>::value) {
        // A list of numbers, booleans or strings: each entry as strictly as a single value
        // (nlohmann's own conversion would turn 64.5 or true into an int).
        if (!v.is_array()) throw ConfigError("");
        T list;
        for (const Json& e : v) {
          typename T::value_type x{};
          convert(key, e, x);
          list.push_back(x);
        }
        out = std::move(list);
      } else {
        out = v.get<T>();
      }
    } catch (const std::exception&) {
      throw ConfigError(where_ + ": key '" + key + "' has invalid value " + v.dump());
    }
  }

  const Json& j_;
  std::string where_;
  std::set<std::string> used_;
  mutable std::set<std::string> asked_;  // every key read or looked for: the valid keys here
};

}  // namespace sgnlf
