#pragma once
// furniture_fem/core/text.hpp: the text helpers every reader uses (record files, CSV tables, mesh
// files): lines with their numbers, trimming, splitting, and strict number parsing. Strict means a
// token is a number only as a whole ("0.05xyz" is not 0.05) and, where a value must be finite, NaN,
// infinity and out-of-range values ("1e400") are refused, so that a bad value is reported with its
// file and line instead of being read as something else.
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace furniture_fem::text {

// ASCII white space (the C locale's isspace, without the locale).
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

// s without white space at either end.
inline std::string_view trim(std::string_view s) {
  std::size_t b = 0, e = s.size();
  while (b < e && is_space(s[b])) ++b;
  while (e > b && is_space(s[e - 1])) --e;
  return s.substr(b, e - b);
}
inline bool is_blank(std::string_view s) { return trim(s).empty(); }

// ASCII case conversion, whatever the locale (other bytes are left as they are).
inline std::string lowercase(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}
inline std::string uppercase(std::string s) {
  for (char& c : s)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return s;
}

// The words of s, separated by white space.
inline std::vector<std::string_view> split_words(std::string_view s) {
  std::vector<std::string_view> w;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const std::size_t b = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > b) w.push_back(s.substr(b, i - b));
  }
  return w;
}

// The fields of one delimited line (CSV, RFC 4180): split at `sep` outside double quotes; quoted
// fields lose their quotes ("" inside them reads as "). Fields are not trimmed.
inline std::vector<std::string> split_fields(std::string_view line, char sep = ',') {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') f.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else f.back() += c;
    } else if (c == '"') quoted = true;
    else if (c == sep) f.emplace_back();
    else f.back() += c;
  }
  return f;
}

// from_chars refuses a leading '+': drop it, but not in front of another sign ("+-1").
inline bool drop_plus(std::string_view& w) {
  if (w.empty() || w.front() != '+') return true;
  w.remove_prefix(1);
  return !w.empty() && w.front() != '-' && w.front() != '+';
}

// Parses the whole of w (no white space, an optional leading '+') as a double, locale-independent.
// NaN and infinity ("nan", "inf") are accepted: use parse_finite where a value must be finite.
// Out-of-range values ("1e400") and trailing characters ("0.05xyz") are refused.
inline bool parse_double(std::string_view w, double& x) {
  if (!drop_plus(w)) return false;
  double v = 0;
  const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
  if (r.ec != std::errc() || r.ptr != w.data() + w.size()) return false;
  x = v;
  return true;
}
inline bool parse_finite(std::string_view w, double& x) {
  double v = 0;
  if (!parse_double(w, v) || !std::isfinite(v)) return false;
  x = v;
  return true;
}
// The whole of w as a decimal integer (an optional sign).
inline bool parse_integer(std::string_view w, long& x) {
  if (!drop_plus(w)) return false;
  long v = 0;
  const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
  if (r.ec != std::errc() || r.ptr != w.data() + w.size()) return false;
  x = v;
  return true;
}

// A text as lines, numbered from 1 (line k is lines[k - 1]): split at '\n', the '\r' of CRLF files
// stripped. A text that ends with '\n' has an empty last line.
struct Lines {
  std::string file;  // where the text came from, for messages
  std::vector<std::string> lines;
  std::size_t size() const { return lines.size(); }
  const std::string& line(long number) const { return lines[static_cast<std::size_t>(number - 1)]; }
};

inline Lines split_lines(std::string file, std::string_view text) {
  Lines t{std::move(file), {}};
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string line(text.substr(start, end - start));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    t.lines.push_back(std::move(line));
    start = end + 1;
  }
  return t;
}

// The whole file as bytes; false if it cannot be opened or read.
inline bool read_file(const std::string& path, std::string& bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream ss;
  ss << in.rdbuf();
  bytes = ss.str();
  return !in.bad();
}

// s without a comment (from `comment` to the end; '\0': none) and trimmed.
inline std::string strip_comment(std::string_view s, char comment = '#') {
  const std::size_t c = comment ? s.find(comment) : std::string_view::npos;
  if (c != std::string_view::npos) s = s.substr(0, c);
  return std::string(trim(s));
}

}  // namespace furniture_fem::text
