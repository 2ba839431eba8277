// The markers a config struct's field list uses (core/config_fields.hpp describes the list):
// omit_when(x), a key written only when not x, and choices(list), an enum written as its
// value's name. Json-free, so that a config header can list its fields without the full
// nlohmann/json; the visitors that read, write and check the list are in config_fields.hpp.
#pragma once
#include <cstddef>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace sgnlf::config {

template <typename T>
struct OmitWhen {
  T value;
};
template <typename T>
OmitWhen<T> omit_when(T value) {
  return {value};
}

// The names of an enum member's values: in the JSON the member is its value's name; any other
// string is refused, naming the key and the names.
template <typename E>
struct Choices {
  const std::pair<E, const char*>* list;
  std::size_t n;
  const std::pair<E, const char*>* begin() const { return list; }
  const std::pair<E, const char*>* end() const { return list + n; }
  std::string names() const {
    std::string s;
    for (const auto& c : *this) s += (s.empty() ? "" : ", ") + std::string(c.second);
    return s;
  }
  const char* name_of(E value) const {
    for (const auto& c : *this)
      if (c.first == value) return c.second;
    throw ConfigError("config: an enum value without a name (" +
                      std::to_string(static_cast<long long>(value)) + "; names: " + names() + ")");
  }
};
template <typename E, std::size_t N>
Choices<E> choices(const std::pair<E, const char*> (&list)[N]) {
  return {list, N};
}

}  // namespace sgnlf::config
