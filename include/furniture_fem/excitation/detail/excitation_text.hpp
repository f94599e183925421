#pragma once
// Internals of furniture_fem/excitation/excitation.hpp: a record file as numbered lines, and a strict number
// parser. Strong-motion files are hand-edited, truncated and converted often; every bad value must be
// reported with its file, line and field rather than read as 0 (what std::atof or >> would do).
#ifndef FURNITURE_FEM_EXCITATION_INTERNAL
#error "furniture_fem/excitation/detail/excitation_text.hpp is internal: include <furniture_fem/excitation/excitation.hpp>"
#endif
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "../../core/errors.hpp"
#include "../../core/text.hpp"

namespace furniture_fem::detail::gm {

inline constexpr double kPi = 3.14159265358979323846;

using text::is_blank;
using text::is_space;
// The record readers keep their lines and fields as strings.
inline std::string trim(std::string_view s) { return std::string(text::trim(s)); }
inline std::string upper(std::string s) { return text::uppercase(std::move(s)); }

inline bool contains(const std::string& s, const char* what) { return s.find(what) != std::string::npos; }

// Short printable excerpt of a bad line for messages (binary junk would garble the terminal).
inline std::string excerpt(const std::string& s, std::size_t max = 40) {
  std::string out;
  for (char c : trim(s)) {
    if (out.size() >= max) {
      out += "...";
      break;
    }
    out += (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '?' : c;
  }
  return out;
}

// The whole file as lines (text::Lines: numbered from 1, CR of CRLF files stripped).
struct TextFile : text::Lines {
  [[noreturn]] void fail(long line, const std::string& field, const std::string& message) const {
    throw InputError(file, line, field, message);
  }
};

// Reads the file; an empty (or all-blank) file is an error of every format. A last '\n' ends the
// last line (it does not start an empty one).
inline TextFile read_text(const std::string& path) {
  std::string bytes;
  if (!text::read_file(path, bytes)) throw InputError(path, 0, "file", "cannot open for reading");
  if (bytes.rfind("\xEF\xBB\xBF", 0) == 0) bytes.erase(0, 3);  // UTF-8 BOM of CSV exports
  TextFile f{text::split_lines(path, bytes)};
  if (!bytes.empty() && bytes.back() == '\n') f.lines.pop_back();
  bool blank = true;
  for (const auto& line : f.lines) blank = blank && is_blank(line);
  if (blank) f.fail(1, "file", "empty file: no header and no samples");
  return f;
}

// Result of parsing the numbers of one line: the first bad token, if any, and its position.
struct LineParse {
  enum Status { ok, not_a_number, not_finite } status = ok;
  std::size_t index = 0;  // index of the bad token among this line's numbers
  std::string token;
};

inline bool is_separator(char c) { return is_space(c) || c == ','; }

// Appends every number of s to out. Accepts C and Fortran notation (".14E-03", "1.0D+02"); numbers
// run together by fixed-width Fortran output ("-.14E-03-.15E-03") are split at the sign. Stops at
// the first token that is not a number or is NaN/inf.
inline LineParse parse_numbers(const std::string& s, std::vector<double>& out) {
  LineParse r;
  const char* p = s.c_str();
  const char* end = p + s.size();
  std::size_t count = 0;
  auto bad = [&](const char* from, LineParse::Status st) {
    const char* e = from;
    while (e < end && !is_separator(*e)) ++e;
    r.status = st;
    r.index = count;
    r.token.assign(from, e);
    return r;
  };
  while (true) {
    while (p < end && is_separator(*p)) ++p;
    if (p >= end) return r;
    char* stop = nullptr;
    double v = std::strtod(p, &stop);
    if (stop == p) return bad(p, LineParse::not_a_number);
    if (stop < end && (*stop == 'D' || *stop == 'd')) {
      // Fortran double-precision exponent: re-parse the token with 'E'.
      const char* e = p;
      while (e < end && !is_separator(*e)) ++e;
      std::string tok(p, e);
      for (char& c : tok)
        if (c == 'D' || c == 'd') c = 'E';
      char* s2 = nullptr;
      v = std::strtod(tok.c_str(), &s2);
      if (static_cast<std::size_t>(s2 - tok.c_str()) != tok.size()) return bad(p, LineParse::not_a_number);
      stop = const_cast<char*>(e);
    }
    const bool run_together = stop < end && (*stop == '-' || *stop == '+') && stop > p &&
                              std::strchr("0123456789.", stop[-1]) != nullptr;
    if (stop < end && !is_separator(*stop) && !run_together) return bad(p, LineParse::not_a_number);
    if (!std::isfinite(v)) return bad(p, LineParse::not_finite);
    out.push_back(v);
    ++count;
    p = stop;
  }
}

// Throws the InputError for a failed parse of line ln; field names the value (e.g. "sample 12").
[[noreturn]] inline void fail_parse(const TextFile& f, long ln, const std::string& field, const LineParse& r) {
  if (r.status == LineParse::not_finite)
    f.fail(ln, field, "NaN or infinite value '" + excerpt(r.token) + "'");
  f.fail(ln, field, "not a number: '" + excerpt(r.token) + "'");
}

// One number that must fill the whole string (header values).
inline bool parse_one(const std::string& s, double& v) {
  std::vector<double> tmp;
  LineParse r = parse_numbers(s, tmp);
  if (r.status != LineParse::ok || tmp.size() != 1) return false;
  v = tmp[0];
  return true;
}

inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A left-to-right scan of one header line: what the readers' header patterns need, each step
// linear in the line's length. std::regex recursed once per character and overflowed the stack on a
// 50 kB header line (issue 13), so the patterns are written out with this instead.
class HeaderScan {
 public:
  explicit HeaderScan(const std::string& line, std::size_t from = 0) : s_(line), p_(from) {}
  std::size_t spaces() {  // skips blanks and tabs; returns how many
    const std::size_t q = p_;
    while (p_ < s_.size() && (s_[p_] == ' ' || s_[p_] == '\t' || s_[p_] == '\r')) ++p_;
    return p_ - q;
  }
  bool word(const char* w) {  // a literal, case-insensitive
    std::size_t q = p_;
    for (; *w; ++w, ++q)
      if (q >= s_.size() || std::toupper(static_cast<unsigned char>(s_[q])) != std::toupper(static_cast<unsigned char>(*w)))
        return false;
    p_ = q;
    return true;
  }
  bool token(const char* chars, std::string& out) {  // one or more characters of the set (case-insensitive)
    const std::size_t q = p_;
    while (p_ < s_.size() && in_set(s_[p_], chars)) ++p_;
    out = s_.substr(q, p_ - q);
    return p_ > q;
  }
  bool at_end() const { return p_ == s_.size(); }

 private:
  static bool in_set(char c, const char* chars) {
    const int u = std::toupper(static_cast<unsigned char>(c));
    for (; *chars; ++chars)
      if (u == std::toupper(static_cast<unsigned char>(*chars))) return true;
    return false;
  }
  const std::string& s_;
  std::size_t p_;
};

inline constexpr const char* digits = "0123456789";
inline constexpr const char* fortran_number = "-+0123456789.ED";

}  // namespace furniture_fem::detail::gm
