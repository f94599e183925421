#pragma once
// Internal: the study's files: CSV fields, exact numbers, atomic writes, the names a study writes, and
// how a folder's study.json differs from the study given.
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/study_files.hpp is internal: include <furniture_fem/study/runner.hpp>"
#endif
#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>

#include "../../core/errors.hpp"
#include "../../scene/json_reader.hpp"

namespace furniture_fem {
namespace detail {

inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}
// The shortest text that reads back as the same double (to_chars: locale-free, exact).
inline std::string exact_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
inline std::string run_file_name(long run) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "run_%08ld.json", run);
  return buf;
}
inline void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  const std::filesystem::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw OutputError("cannot open '" + tmp.string() + "' for writing");
    f << text;
    f.flush();
    if (!f) throw OutputError("error while writing '" + tmp.string() + "' (disk full?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw OutputError("cannot rename '" + tmp.string() + "' to '" + path.string() + "'");
  }
}
// The files a study writes, by name: only these are removed when a study's folder is reused.
inline const std::vector<std::string>& study_result_files() {
  static const std::vector<std::string> files{"study.json",       "summary.json",  "realisations.csv",
                                              "probabilities.csv", "distributions.csv", "fragility.csv",
                                              "comparisons.csv",   "statistics.json", "fragility.png",
                                              "max_tilt_vs_intensity.png", "outcome_histograms.png"};
  return files;
}

// The keys where JSON `was` and `now` differ, as "key.path: new (was old)", the first `room` in key
// order; `count` counts them all. A key present on one side only is "(absent)" on the other.
inline void json_differences(const nlohmann::json* was, const nlohmann::json* now, const std::string& path,
                             std::vector<std::string>& out, std::size_t room, std::size_t& count) {
  if (was && now && *was == *now) return;
  const auto show = [](const nlohmann::json* v) { return v ? json_io::ObjectReader::brief(*v, 60) : "(absent)"; };
  const auto member = [](const nlohmann::json* v, const std::string& k) -> const nlohmann::json* {
    return v && v->is_object() && v->contains(k) ? &(*v)[k] : nullptr;
  };
  const auto element = [](const nlohmann::json* v, std::size_t i) -> const nlohmann::json* {
    return v && v->is_array() && i < v->size() ? &(*v)[i] : nullptr;
  };
  if (was && now && was->is_object() && now->is_object()) {
    for (auto it = was->begin(); it != was->end(); ++it)
      json_differences(&it.value(), member(now, it.key()), json_io::key_path(path, it.key()), out, room, count);
    for (auto it = now->begin(); it != now->end(); ++it)
      if (!was->contains(it.key())) json_differences(nullptr, &it.value(), json_io::key_path(path, it.key()), out, room, count);
  } else if (was && now && was->is_array() && now->is_array()) {
    for (std::size_t i = 0; i < std::max(was->size(), now->size()); ++i)
      json_differences(element(was, i), element(now, i), json_io::index_path(path, i), out, room, count);
  } else {
    if (out.size() < room) out.push_back((path.empty() ? "(top level)" : path) + ": " + show(now) + " (was " + show(was) + ")");
    ++count;
  }
}

// "a: 2 (was 1); b: ...; and 3 more": how the study recorded in a folder differs from the one given.
inline std::string study_differences(const nlohmann::json& was, const nlohmann::json& now, std::size_t room = 4) {
  std::vector<std::string> out;
  std::size_t count = 0;
  json_differences(&was, &now, "", out, room, count);
  std::string text;
  for (const auto& d : out) text += (text.empty() ? "" : "; ") + d;
  if (count > out.size()) text += "; and " + std::to_string(count - out.size()) + " more";
  return text;
}
}  // namespace detail

}  // namespace furniture_fem
