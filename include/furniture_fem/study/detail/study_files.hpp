#pragma once
// Internal: the study's files: CSV fields, exact numbers, atomic writes, the names a study writes.
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/study_files.hpp is internal: include <furniture_fem/study/runner.hpp>"
#endif
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include "../../core/errors.hpp"

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
}  // namespace detail

}  // namespace furniture_fem
