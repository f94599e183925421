#pragma once
// furniture_fem/scene/json_reader.hpp: strict reading of JSON input files (scenes, studies). Every
// value is read through ObjectReader, which knows the key path ("items[2].yaw_deg"), rejects unknown
// keys and wrong types, and throws InputError naming the file, the path and the offending value.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../core/model.hpp"
#include "../core/errors.hpp"

namespace furniture_fem::json_io {

using json = nlohmann::json;

// Names of an enumeration's values, as written in scene files.
template <class E, size_t N>
using EnumNames = std::array<std::pair<E, std::string_view>, N>;

template <class E, size_t N>
std::string enum_name(const EnumNames<E, N>& names, E value) {
  for (auto [e, s] : names)
    if (e == value) return std::string(s);
  return "unknown";
}

template <class E, size_t N>
std::string enum_choices(const EnumNames<E, N>& names) {
  std::string out;
  for (auto [e, s] : names) out += (out.empty() ? "" : ", ") + std::string(s);
  return out;
}

inline std::string key_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
inline std::string index_path(const std::string& parent, size_t i) { return parent + "[" + std::to_string(i) + "]"; }

// The reader of one JSON object at a key path.
class ObjectReader {
 public:
  ObjectReader(const json& j, std::string path, const std::string& source) : j_(j), path_(std::move(path)), source_(source) {
    if (!j_.is_object()) fail(path_, "expected an object, got " + describe(j_));
  }

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw InputError(source_, 0, path.empty() ? "(top level)" : path, message);
  }
  static std::string describe(const json& v) {
    const std::string type = v.is_string() ? "a string" : v.is_boolean() ? "a boolean" : v.is_number() ? "a number"
                             : v.is_array() ? "an array" : v.is_object() ? "an object" : "null";
    std::string text = brief(v, 60);
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    return type + " (" + text + ")";
  }
  // The start of v's JSON text, about `room` characters, without serialising all of a large value.
  static std::string brief(const json& v, std::size_t room) {
    if (!v.is_structured()) return v.dump();
    std::string out = v.is_array() ? "[" : "{";
    for (auto it = v.begin(); it != v.end() && out.size() <= room; ++it) {
      if (it != v.begin()) out += ",";
      if (v.is_object()) out += json(it.key()).dump() + ":";
      out += brief(*it, room - std::min(room, out.size()));
    }
    return out + (v.is_array() ? "]" : "}");
  }

  // Every key present must be one of `allowed`: a misspelt key is an error, not a silent default.
  void allow_only(const std::vector<std::string_view>& allowed, std::string_view what = "key") const {
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
        std::string list;
        for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
        fail(key_path(path_, it.key()), "unknown " + std::string(what) + "; allowed here: " + list);
      }
  }

  bool has(std::string_view key) const { return j_.contains(std::string(key)); }
  const json& raw_object() const { return j_; }
  const json& raw(std::string_view key) const { return j_.at(std::string(key)); }
  std::string path(std::string_view key) const { return key_path(path_, key); }
  const std::string& path() const { return path_; }
  const std::string& source() const { return source_; }

  std::optional<double> optional_number(std::string_view key) const {
    if (!has(key)) return std::nullopt;
    const json& v = raw(key);
    if (!v.is_number()) fail(path(key), "expected a number, got " + describe(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(path(key), "expected a finite number, got " + v.dump());
    return d;
  }
  double number(std::string_view key, double fallback) const { return optional_number(key).value_or(fallback); }

  std::optional<long long> optional_integer(std::string_view key) const {
    if (!has(key)) return std::nullopt;
    const json& v = raw(key);
    if (!v.is_number_integer()) fail(path(key), "expected an integer, got " + describe(v));
    return v.get<long long>();
  }
  long long integer(std::string_view key, long long fallback) const { return optional_integer(key).value_or(fallback); }

  bool boolean(std::string_view key, bool fallback) const {
    if (!has(key)) return fallback;
    const json& v = raw(key);
    if (!v.is_boolean()) fail(path(key), "expected true or false, got " + describe(v));
    return v.get<bool>();
  }

  std::optional<std::string> optional_string(std::string_view key) const {
    if (!has(key)) return std::nullopt;
    const json& v = raw(key);
    if (!v.is_string()) fail(path(key), "expected a string, got " + describe(v));
    return v.get<std::string>();
  }
  std::string string(std::string_view key, const std::string& fallback) const {
    return optional_string(key).value_or(fallback);
  }

  std::optional<Vec3> optional_vec3(std::string_view key) const {
    if (!has(key)) return std::nullopt;
    const json& v = raw(key);
    if (!v.is_array() || v.size() != 3) fail(path(key), "expected an array of 3 numbers, got " + describe(v));
    Vec3 out;
    for (size_t i = 0; i < 3; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
        fail(index_path(path(key), i), "expected a finite number, got " + describe(v[i]));
      out[static_cast<int>(i)] = v[i].get<double>();
    }
    return out;
  }
  Vec3 vec3(std::string_view key, const Vec3& fallback) const { return optional_vec3(key).value_or(fallback); }

  template <class E, size_t N>
  E enumeration(std::string_view key, const EnumNames<E, N>& names, E fallback, std::string_view what) const {
    const auto s = optional_string(key);
    if (!s) return fallback;
    for (auto [e, name] : names)
      if (name == *s) return e;
    fail(path(key), "unknown " + std::string(what) + " \"" + *s + "\"; expected one of: " + enum_choices(names));
  }

  // Range checks, with the offending value in the message.
  void require(bool ok, std::string_view key, const std::string& rule) const {
    if (!ok) fail(path(key), rule + " (got " + brief(raw(key), 60) + ")");
  }
  void positive(std::string_view key) const {
    if (has(key)) require(raw(key).get<double>() > 0, key, "must be positive");
  }
  void non_negative(std::string_view key) const {
    if (has(key)) require(raw(key).get<double>() >= 0, key, "must not be negative");
  }
  void in_range(std::string_view key, double lo, double hi) const {
    if (has(key)) {
      const double v = raw(key).get<double>();
      require(v >= lo && v <= hi, key, "must lie in [" + detail::fmt(lo) + ", " + detail::fmt(hi) + "]");
    }
  }

  // An array under `key` (absent: empty); each element is handed to `read(element, path)`.
  template <class F>
  void array(std::string_view key, F&& read) const {
    if (!has(key)) return;
    const json& v = raw(key);
    if (!v.is_array()) fail(path(key), "expected an array, got " + describe(v));
    for (size_t i = 0; i < v.size(); ++i) read(v[i], index_path(path(key), i));
  }

  ObjectReader object(std::string_view key) const { return ObjectReader(raw(key), path(key), source_); }

 private:
  const json& j_;
  std::string path_;
  const std::string& source_;
};

inline json to_json_vec3(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

}  // namespace furniture_fem::json_io
