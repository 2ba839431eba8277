// A config struct described once. The struct lists its fields in one static member template,
//
//   template <class Self, class V> static void fields(Self& s, V& v) {
//     v("levels", s.levels, 1, 32);          // key, member, allowed range [lo, hi]
//     v("jitter", s.jitter);                 // key, member (no range: bools, strings, lists)
//     v("start_step", s.start_step, 0L, 9L, omit_when(0L));  // written only when not 0
//     v("form", s.form, choices(kForms));    // an enum, written as its name (kForms: its
//                                            // {value, "name"} pairs)
//     v.section("grid", s.grid);             // a nested struct with its own fields() list
//     v.optional("geometric", s.geometric);  // a std::optional of one: on exactly when present
//     v.object("psi", s.psi);                // a nested config with its own from_json/to_json
//   }
//
// and the visitors below drive from that one list the strict reader (ConfigReader: unknown keys
// and values of the wrong type refused, naming the config and key), the writer, the range
// checks of validate() (check_range: the key and value named) and the schema description. The
// config hash is the writer's JSON hashed, so it follows the same list. A nested config
// (T::from_json(json, where), t.to_json()) is read and written by its own functions; its
// checks stay with the parent's validate(), which calls the nested one's. omit_when(x) marks a
// key added after results were committed: it is written only when not x, so their configs and
// hashes stay as they were. A nested config that has its own field list is described in the
// schema with its keys ("fields") as well. An optional section (v.optional) is on exactly when
// its key is present in the JSON: absent, the member is reset (whatever the struct's default);
// present, its keys are read over the struct's default; written only when engaged. Its
// presence is its only switch: an "enabled" key inside it is refused (refuse_enabled_key).
// The markers omit_when and choices are in the json-free
// core/config_choices.hpp, which is all a config header needs to list its fields.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include "core/config.hpp"
#include "core/config_choices.hpp"

namespace sgnlf::config {

namespace detail {
template <typename T, typename V, typename = void>
struct HasFields : std::false_type {};
template <typename T, typename V>
struct HasFields<T, V, std::void_t<decltype(T::fields(std::declval<const T&>(), std::declval<V&>()))>>
    : std::true_type {};
}  // namespace detail

// The switch key of the old configs: a section's presence now says whether it is on, so an
// "enabled" key inside `section` (the reader of the section named `key`) is refused with what
// to do instead.
inline void refuse_enabled_key(ConfigReader& section, const std::string& key) {
  if (!section.has("enabled")) return;
  throw ConfigError(section.where() + ": 'enabled' is not a key: a section is on exactly when it "
                    "is present. To turn '" + key + "' off, remove the section (in overrides: \"" +
                    key + "\": null); to keep it on, remove the 'enabled' key");
}

// Reads each listed key present in the reader's object into its member.
class FieldReader {
 public:
  explicit FieldReader(ConfigReader& r) : r_(r) {}
  template <typename T>
  void operator()(const char* key, T& member) {
    r_.get(key, member);
  }
  template <typename T, typename L>
  void operator()(const char* key, T& member, L, L) {
    r_.get(key, member);
  }
  template <typename T, typename L>
  void operator()(const char* key, T& member, L, L, OmitWhen<T>) {
    r_.get(key, member);
  }
  template <typename T>
  void operator()(const char* key, T& member, OmitWhen<T>) {
    r_.get(key, member);
  }
  template <typename E>
  void operator()(const char* key, E& member, Choices<E> choices) {
    if (!r_.has(key)) return;
    std::string name;
    r_.get(key, name);
    for (const auto& c : choices)
      if (name == c.second) {
        member = c.first;
        return;
      }
    throw ConfigError(r_.where() + ": key '" + key + "' has invalid value \"" + name + "\" (" +
                      choices.names() + ")");
  }
  template <typename S>
  void section(const char* key, S& member) {
    ConfigReader c = r_.child(key);
    FieldReader v(c);
    S::fields(member, v);
    c.finish();
  }
  template <typename S>
  void optional(const char* key, std::optional<S>& member) {
    if (!r_.has(key)) {
      member.reset();
      return;
    }
    ConfigReader c = r_.child(key);
    refuse_enabled_key(c, key);
    S s = member.value_or(S{});
    FieldReader v(c);
    S::fields(s, v);
    c.finish();
    member = std::move(s);
  }
  template <typename T>
  void object(const char* key, T& member) {
    if (!r_.has(key)) return;
    Json sub;
    r_.get(key, sub);
    member = T::from_json(sub, r_.where() + "." + key);
  }

 private:
  ConfigReader& r_;
};

// Writes every listed member under its key.
class FieldWriter {
 public:
  explicit FieldWriter(Json& j) : j_(j) {}
  template <typename T>
  void operator()(const char* key, const T& member) {
    j_[key] = member;
  }
  template <typename T, typename L>
  void operator()(const char* key, const T& member, L, L) {
    j_[key] = member;
  }
  template <typename T, typename L>
  void operator()(const char* key, const T& member, L, L, OmitWhen<T> omit) {
    if (!(member == omit.value)) j_[key] = member;
  }
  template <typename T>
  void operator()(const char* key, const T& member, OmitWhen<T> omit) {
    if (!(member == omit.value)) j_[key] = member;
  }
  template <typename E>
  void operator()(const char* key, const E& member, Choices<E> choices) {
    j_[key] = choices.name_of(member);
  }
  template <typename S>
  void section(const char* key, const S& member) {
    Json sub = Json::object();
    FieldWriter v(sub);
    S::fields(member, v);
    j_[key] = sub;
  }
  template <typename S>
  void optional(const char* key, const std::optional<S>& member) {
    if (member) section(key, *member);
  }
  template <typename T>
  void object(const char* key, const T& member) {
    j_[key] = member.to_json();
  }

 private:
  Json& j_;
};

// Checks every ranged member, in list order (the first one outside its range is named).
class FieldChecker {
 public:
  explicit FieldChecker(std::string where) : where_(std::move(where)) {}
  template <typename T>
  void operator()(const char*, const T&) {}
  template <typename T, typename L>
  void operator()(const char* key, const T& member, L lo, L hi) {
    check_range<T>(where_, key, member, T(lo), T(hi));
  }
  template <typename T, typename L>
  void operator()(const char* key, const T& member, L lo, L hi, OmitWhen<T>) {
    (*this)(key, member, lo, hi);
  }
  template <typename T>
  void operator()(const char*, const T&, OmitWhen<T>) {}
  template <typename E>
  void operator()(const char*, const E&, Choices<E>) {}  // the reader takes only the names
  template <typename S>
  void section(const char* key, const S& member) {
    FieldChecker v(where_ + "." + key);
    S::fields(member, v);
  }
  template <typename S>
  void optional(const char* key, const std::optional<S>& member) {
    if (member) section(key, *member);
  }
  template <typename T>
  void object(const char*, const T&) {}

 private:
  std::string where_;
};

// The schema: per key its JSON type, default (the struct's value) and range when it has one.
class FieldDescriber {
 public:
  explicit FieldDescriber(Json& j) : j_(j) {}
  template <typename T>
  void operator()(const char* key, const T& member) {
    j_[key] = Json{{"type", type_of<T>()}, {"default", member}};
  }
  template <typename T, typename L>
  void operator()(const char* key, const T& member, L lo, L hi) {
    j_[key] = Json{{"type", type_of<T>()}, {"default", member}, {"min", T(lo)}, {"max", T(hi)}};
  }
  template <typename T, typename L>
  void operator()(const char* key, const T& member, L lo, L hi, OmitWhen<T>) {
    (*this)(key, member, lo, hi);
    j_[key]["written"] = "only when not the default";
  }
  template <typename T>
  void operator()(const char* key, const T& member, OmitWhen<T>) {
    (*this)(key, member);
    j_[key]["written"] = "only when not the default";
  }
  template <typename E>
  void operator()(const char* key, const E& member, Choices<E> choices) {
    Json names = Json::array();
    for (const auto& c : choices) names.push_back(c.second);
    j_[key] = Json{{"type", "string"}, {"default", choices.name_of(member)}, {"one_of", names}};
  }
  template <typename S>
  void section(const char* key, const S& member) {
    Json sub = Json::object();
    FieldDescriber v(sub);
    S::fields(member, v);
    j_[key] = sub;
  }
  // An optional section: its keys (at the struct's defaults) under "fields".
  template <typename S>
  void optional(const char* key, const std::optional<S>& member) {
    Json sub = Json::object();
    FieldDescriber v(sub);
    const S d = member.value_or(S{});
    S::fields(d, v);
    j_[key] = Json{{"type", "object"},
                   {"optional", "on exactly when present; absent: off"},
                   {"fields", sub}};
  }
  // A nested config: its default object, and its keys when it has a field list.
  template <typename T>
  void object(const char* key, const T& member) {
    j_[key] = Json{{"type", "object"}, {"default", member.to_json()}};
    if constexpr (detail::HasFields<T, FieldDescriber>::value) {
      Json sub = Json::object();
      FieldDescriber v(sub);
      T::fields(member, v);
      j_[key]["fields"] = sub;
    }
  }

 private:
  template <typename T>
  static const char* type_of() {
    if constexpr (std::is_same_v<T, bool>) return "boolean";
    else if constexpr (std::is_integral_v<T>) return "integer";
    else if constexpr (std::is_floating_point_v<T>) return "number";
    else if constexpr (std::is_same_v<T, std::string>) return "string";
    else return "array";
  }
  Json& j_;
};

// The struct's object under `key` of `r` (absent: the defaults stay), read strictly.
template <typename S>
void read_fields(ConfigReader& r, const std::string& key, S& s) {
  ConfigReader c = r.child(key);
  FieldReader v(c);
  S::fields(s, v);
  c.finish();
}

// The struct's keys read from `r`'s own object (the caller finishes `r`).
template <typename S>
void read_fields_here(ConfigReader& r, S& s) {
  FieldReader v(r);
  S::fields(s, v);
}

template <typename S>
Json write_fields(const S& s) {
  Json j = Json::object();
  FieldWriter v(j);
  S::fields(s, v);
  return j;
}

template <typename S>
void check_fields(const S& s, const std::string& where) {
  FieldChecker v(where);
  S::fields(s, v);
}

// The schema of S at its defaults: {key: {type, default[, min, max][, one_of][, fields]}}.
// GCC 12 at -O2 and above reports the destructor of the default config, for configs with nested
// optional sections, as reading uninitialised strings (-Wmaybe-uninitialized): a false
// positive, which CI's -Werror would make an error.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
template <typename S>
Json describe_fields() {
  const S s{};
  Json j = Json::object();
  FieldDescriber v(j);
  S::fields(s, v);
  return j;
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

}  // namespace sgnlf::config
