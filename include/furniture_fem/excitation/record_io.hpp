#pragma once
// furniture_fem/excitation/record_io.hpp: Reading and writing records: PEER NGA AT2, K-NET/KiK-net ASCII, JMA CSV, plain columns.
// Part of furniture_fem/excitation/excitation.hpp (which includes every part); SI units throughout.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "../core/errors.hpp"
#include "record.hpp"
#define FURNITURE_FEM_EXCITATION_INTERNAL
#include "detail/excitation_text.hpp"
#undef FURNITURE_FEM_EXCITATION_INTERNAL

namespace furniture_fem {

// ---------------------------------------------------------------------------------------------
// Reading and writing
// ---------------------------------------------------------------------------------------------

enum class Unit { g, gal, m_s2 };

// m/s^2 per unit.
[[nodiscard]] constexpr double unit_factor(Unit u) noexcept {
  switch (u) {
    case Unit::g: return standard_gravity;
    case Unit::gal: return 0.01;
    case Unit::m_s2: return 1.0;
  }
  return 1.0;
}

enum class Format { automatic, peer_at2, knet, jma_csv, columns };

// Plain-column files: (time, value) pairs, or bare values dt apart with any number per line.
enum class Layout { automatic /* values if dt > 0, else time_value */, time_value, values };

struct ReadOptions {
  Unit unit = Unit::m_s2;    // columns: unit of the values (the other formats say theirs)
  double dt = 0;             // columns: sample spacing of bare values (selects Layout::values)
  int skip_lines = 0;        // columns: raw lines to ignore at the top (e.g. a "0.02 0.50" dt line)
  Layout layout = Layout::automatic;
  int component = 0;         // JMA CSV: 0 NS, 1 EW, 2 UD
  bool remove_mean = true;   // K-NET/KiK-net: subtract the mean count (the NIED convention)
};

namespace detail::gm {

inline std::string file_stem(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  std::string s = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = s.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? s : s.substr(0, dot);
}

// Appends the numbers of line ln to out, naming a bad one "sample k" (1-based in the record).
inline void parse_samples(const TextFile& f, long ln, std::vector<double>& out) {
  const std::size_t before = out.size();
  const LineParse r = parse_numbers(f.lines[ln - 1], out);
  if (r.status != LineParse::ok) fail_parse(f, ln, "sample " + std::to_string(before + r.index + 1), r);
}

// Converts the samples out[from..] of line ln to m/s^2 (times factor). A value the conversion takes
// past the range of a double (1e308 in g) is bad input: it gave an infinite sample before, found by
// fuzzing (docs/fuzzing.md).
inline void scale_samples(const TextFile& f, long ln, std::vector<double>& out, std::size_t from, double factor,
                          const std::string& field = "sample") {
  for (std::size_t k = from; k < out.size(); ++k) {
    const double raw = out[k];
    out[k] *= factor;
    if (!std::isfinite(out[k]))
      f.fail(ln, field == "sample" ? "sample " + std::to_string(k + 1) : field,
             "value " + num(raw) + " is out of range once converted to m/s^2 (x " + num(factor) + ")");
  }
}

inline bool is_comment(const std::string& line) {
  const std::string t = trim(line);
  return !t.empty() && (t[0] == '#' || t[0] == ';');
}

inline bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Does line 4 hold the PEER "NPTS = n, DT = dt" (anywhere in the line) or the older "n dt NPTS, DT"?
inline bool match_npts(const std::string& line, std::string& npts, std::string& dt) {
  const std::string up = upper(line);
  for (std::size_t at = up.find("NPTS"); at != std::string::npos; at = up.find("NPTS", at + 1)) {
    HeaderScan m(line, at + 4);
    m.spaces();
    if (!m.word("=")) continue;
    m.spaces();
    if (!m.token(digits, npts)) continue;
    m.spaces();
    m.word(",");
    m.spaces();
    if (!m.word("DT")) continue;
    m.spaces();
    if (!m.word("=")) continue;
    m.spaces();
    if (m.token(fortran_number, dt)) return true;
  }
  HeaderScan old(line);
  old.spaces();
  if (!old.token(digits, npts) || !old.spaces() || !old.token(fortran_number, dt) || !old.spaces()) return false;
  if (!old.word("NPTS")) return false;
  old.spaces();
  if (!old.word(",")) return false;
  old.spaces();
  return old.word("DT");
}

// "<number> [unit]" and nothing else, as in "100Hz" or " 100 Hz " (K-NET, JMA sampling rates).
inline bool match_number_unit(const std::string& text, const char* unit, std::string& number) {
  HeaderScan m(text);
  m.spaces();
  if (!m.token("0123456789.E+", number)) return false;
  m.spaces();
  m.word(unit);
  m.spaces();
  return m.at_end();
}

// K-NET's scale factor "3920(gal)/6182761".
inline bool match_scale(const std::string& text, std::string& numerator, std::string& denominator) {
  HeaderScan m(text);
  m.spaces();
  if (!m.token("-+0123456789.E", numerator)) return false;
  m.spaces();
  if (!m.word("(gal)")) return false;
  m.spaces();
  if (!m.word("/")) return false;
  m.spaces();
  if (!m.token("-+0123456789.E", denominator)) return false;
  m.spaces();
  return m.at_end();
}

// What a strong-motion record can be: sampled between 100 kHz and 1 Hz, with at least two samples.
// Outside, the file is wrong (a header typo, a unit read as a step); it ran before (issue 13).
inline constexpr double min_record_dt = 1e-5, max_record_dt = 1.0;  // s
inline std::string record_dt_problem(double dt) {
  if (dt >= min_record_dt && dt <= max_record_dt) return {};
  return "implausible time step " + num(dt) + " s (a strong-motion record is sampled every 1e-5 to 1 s)";
}

inline void check_record(const Record& r, const char* what) {
  if (!(r.dt > 0) || !std::isfinite(r.dt))
    throw InputError(std::string(what) + ": record '" + r.name + "' has dt = " + num(r.dt) +
                                " (must be positive)");
  if (r.acc.empty()) throw InputError(std::string(what) + ": record '" + r.name + "' has no samples");
}

}  // namespace detail::gm

// PEER NGA .AT2: 4 header lines (title; event, date, station, component; "ACCELERATION TIME SERIES
// IN UNITS OF G"; "NPTS = 7500, DT = .020 SEC"), then the samples, 5 per line in Fortran E format.
[[nodiscard]] inline Record read_peer_at2(const std::string& path) {
  using namespace detail::gm;
  const TextFile f = read_text(path);
  if (f.lines.size() < 4)
    f.fail(4, "NPTS", "missing header: the file ends before line 4 'NPTS = n, DT = dt SEC' of the PEER header");
  std::string npts_s, dt_s;
  if (!match_npts(f.lines[3], npts_s, dt_s))
    f.fail(4, "NPTS", "missing header line 'NPTS = n, DT = dt SEC', found '" + excerpt(f.lines[3]) + "'");
  if (npts_s.size() > 9) f.fail(4, "NPTS", "implausible sample count " + excerpt(npts_s));
  const long npts = std::stol(npts_s);
  double dt = 0;
  if (!parse_one(dt_s, dt) || !(dt > 0)) f.fail(4, "DT", "not a positive time step: '" + excerpt(dt_s) + "'");
  if (const std::string why = record_dt_problem(dt); !why.empty()) f.fail(4, "DT", why);
  if (npts < 2) f.fail(4, "NPTS", "a record needs at least 2 samples (NPTS = " + npts_s + ")");

  const std::string units = upper(f.lines[2]);
  if (!contains(units, "ACCEL"))
    f.fail(3, "units", "not an acceleration time series: '" + excerpt(f.lines[2]) + "'");
  double factor = 0;
  const std::size_t g = units.find("UNITS OF G");
  // "UNITS OF G" but not "UNITS OF GAL": the G must end the word.
  const char after = g != std::string::npos && g + 10 < units.size() ? units[g + 10] : ' ';
  const bool is_g = g != std::string::npos && !((after >= 'A' && after <= 'Z') || (after >= '0' && after <= '9') ||
                                                after == '/');
  if (is_g)
    factor = standard_gravity;
  else if (contains(units, "CM/S") || contains(units, "GAL"))
    factor = 0.01;
  else if (contains(units, "M/S"))
    factor = 1.0;
  else
    f.fail(3, "units", "unknown unit in '" + excerpt(f.lines[2]) + "' (expected G, CM/S/S or M/S/S)");

  Record r;
  r.name = trim(f.lines[1]);
  r.source = path + " (PEER NGA AT2)";
  r.dt = dt;
  // What the header claims is checked against the file before any memory is taken for it: at most
  // 8 samples per line (NPTS = 999999999 reserved 8 GB before, then bad_alloc without a file name).
  r.acc.reserve(std::min(static_cast<std::size_t>(npts), 8 * f.lines.size()));
  for (std::size_t i = 4; i < f.lines.size(); ++i) {
    const long ln = long(i) + 1;
    const std::size_t before = r.acc.size();
    parse_samples(f, ln, r.acc);
    if (long(r.acc.size()) > npts)
      f.fail(ln, "NPTS", "more samples than NPTS = " + std::to_string(npts) + " (line 4)");
    scale_samples(f, ln, r.acc, before, factor);
  }
  if (long(r.acc.size()) != npts)
    f.fail(4, "NPTS", "header says " + std::to_string(npts) + " samples but the file has " +
                          std::to_string(r.acc.size()));
  return r;
}

// K-NET / KiK-net ASCII (NIED): a "Key  value" header ("Sampling Freq(Hz) 100Hz", "Scale Factor
// 3920(gal)/6182761", ...) closed by "Memo.", then integer counts 8 per line. Acceleration in gal is
// count * 3920 / 6182761; NIED's convention is to subtract the mean first.
[[nodiscard]] inline Record read_knet(const std::string& path, bool remove_mean = true) {
  using namespace detail::gm;
  const TextFile f = read_text(path);
  double freq = 0, num_gal = 0, den = 0;
  std::string station, dir, origin;
  std::size_t i = 0;
  bool memo = false;
  for (; i < f.lines.size() && !memo; ++i) {
    const std::string line = trim(f.lines[i]);
    const long ln = long(i) + 1;
    std::vector<double> probe;
    if (!line.empty() && parse_numbers(line, probe).status == LineParse::ok && !probe.empty()) break;  // data
    std::string m1, m2;
    if (starts_with(line, "Sampling Freq")) {
      const std::size_t p = line.find(')');
      const std::string v = p == std::string::npos ? line.substr(13) : line.substr(p + 1);
      if (!match_number_unit(v, "Hz", m1) || !parse_one(m1, freq) || !(freq > 0))
        f.fail(ln, "Sampling Freq(Hz)", "not a positive frequency: '" + excerpt(v) + "'");
      if (const std::string why = record_dt_problem(1.0 / freq); !why.empty()) f.fail(ln, "Sampling Freq(Hz)", why);
    } else if (starts_with(line, "Scale Factor")) {
      const std::string v = line.substr(12);
      if (!match_scale(v, m1, m2) || !parse_one(m1, num_gal) || !parse_one(m2, den) ||
          !(den != 0) || !std::isfinite(num_gal / den))
        f.fail(ln, "Scale Factor", "expected 'gal(gal)/counts' like 3920(gal)/6182761, found '" + excerpt(v) + "'");
    } else if (starts_with(line, "Station Code")) {
      station = trim(line.substr(12));
    } else if (starts_with(line, "Dir.")) {
      dir = trim(line.substr(4));
    } else if (starts_with(line, "Origin Time")) {
      origin = trim(line.substr(11));
    } else if (starts_with(line, "Memo")) {
      memo = true;
    }
  }
  const long at = long(std::min(i + (memo ? 0 : 1), f.lines.size()));
  if (den == 0) f.fail(at, "Scale Factor", "missing header line 'Scale Factor  3920(gal)/6182761'");
  if (freq == 0) f.fail(at, "Sampling Freq(Hz)", "missing header line 'Sampling Freq(Hz) 100Hz'");
  if (!memo) f.fail(at, "Memo.", "missing header line 'Memo.' that ends the K-NET header");

  Record r;
  r.name = station.empty() ? file_stem(path) : station + (dir.empty() ? "" : " " + dir);
  r.source = path + " (K-NET/KiK-net ASCII" + (origin.empty() ? "" : ", origin " + origin) + ")";
  r.dt = 1.0 / freq;
  std::vector<std::size_t> line_start;  // index of each data line's first sample, for messages
  const std::size_t first_data = i;
  for (; i < f.lines.size(); ++i) {
    line_start.push_back(r.acc.size());
    parse_samples(f, long(i) + 1, r.acc);
  }
  if (r.acc.size() < 2) f.fail(long(f.lines.size()), "samples", "a record needs at least 2 samples after the header");
  const double to_gal = num_gal / den;
  double mean = 0;
  if (remove_mean) {
    for (double c : r.acc) mean += c;
    mean /= double(r.acc.size());
    if (!std::isfinite(mean)) {  // the sum overflowed (two counts of 1e308): sum count / n instead
      mean = 0;
      for (double c : r.acc) mean += c / double(r.acc.size());
    }
  }
  for (std::size_t k = 0; k < r.acc.size(); ++k) {
    const double count = r.acc[k];
    r.acc[k] = (count - mean) * to_gal * 0.01;
    if (!std::isfinite(r.acc[k])) {
      const auto at = std::upper_bound(line_start.begin(), line_start.end(), k) - line_start.begin();
      f.fail(long(first_data) + long(at), "sample " + std::to_string(k + 1),
             "count " + num(count) + (remove_mean ? " less the mean count " + num(mean) : std::string()) +
                 " is out of range once converted to m/s^2 (x " + num(to_gal * 0.01) + ")");
    }
  }
  return r;
}

// JMA CSV (the Japan Meteorological Agency's strong-motion files): "KEY= value" header lines
// (SITE CODE, SAMPLING RATE= 100Hz, UNIT = gal, INITIAL TIME, ...), a column line "NS,EW,UD", then
// one row of three values per sample. Returns the components in the order NS, EW, UD.
[[nodiscard]] inline std::array<Record, 3> read_jma_csv(const std::string& path) {
  using namespace detail::gm;
  const TextFile f = read_text(path);
  static const char* const names[3] = {"NS", "EW", "UD"};
  double rate = 0, factor = 0;
  std::string site, initial;
  long rate_line = 0, unit_line = 0;
  int column_of[3] = {-1, -1, -1};  // component -> CSV column
  std::size_t i = 0;
  for (; i < f.lines.size(); ++i) {
    const std::string line = trim(f.lines[i]);
    const long ln = long(i) + 1;
    if (line.empty()) continue;
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) {
      const std::string key = upper(trim(line.substr(0, eq))), value = trim(line.substr(eq + 1));
      std::string number;
      if (key == "SITE CODE") {
        site = value;
      } else if (key == "INITIAL TIME") {
        initial = value;
      } else if (key == "SAMPLING RATE") {
        rate_line = ln;
        if (!match_number_unit(value, "Hz", number) || !parse_one(number, rate) || !(rate > 0))
          f.fail(ln, "SAMPLING RATE", "not a positive frequency: '" + excerpt(value) + "'");
        if (const std::string why = record_dt_problem(1.0 / rate); !why.empty()) f.fail(ln, "SAMPLING RATE", why);
      } else if (key == "UNIT") {
        unit_line = ln;
        const std::string u = upper(value);
        if (u == "GAL" || u == "CM/S2" || u == "CM/S^2" || u == "CM/S/S")
          factor = 0.01;
        else if (u == "G")
          factor = standard_gravity;
        else if (u == "M/S2" || u == "M/S^2" || u == "M/S/S")
          factor = 1.0;
        else
          f.fail(ln, "UNIT", "unknown unit '" + excerpt(value) + "' (expected gal, g or m/s2)");
      }
      continue;
    }
    // The column line names the three components, in any order.
    std::string cols = upper(line);
    for (char& c : cols)
      if (c == ',') c = ' ';
    std::vector<std::string> tokens;
    for (std::size_t p = 0; p < cols.size();) {
      while (p < cols.size() && cols[p] == ' ') ++p;
      std::size_t e = p;
      while (e < cols.size() && cols[e] != ' ') ++e;
      if (e > p) tokens.push_back(cols.substr(p, e - p));
      p = e;
    }
    bool header = tokens.size() == 3;
    for (int c = 0; c < 3 && header; ++c) {
      column_of[c] = -1;
      for (int k = 0; k < 3; ++k)
        if (tokens[k] == names[c]) column_of[c] = k;
      header = column_of[c] >= 0;
    }
    if (header) {
      ++i;
      break;
    }
    std::vector<double> probe;
    if (parse_numbers(line, probe).status == LineParse::ok)
      f.fail(ln, "NS,EW,UD", "missing column header line 'NS,EW,UD' before the samples");
    column_of[0] = column_of[1] = column_of[2] = -1;
  }
  const long header_end = long(i);
  if (column_of[0] < 0) f.fail(header_end, "NS,EW,UD", "missing column header line 'NS,EW,UD'");
  if (rate_line == 0) f.fail(header_end, "SAMPLING RATE", "missing header line 'SAMPLING RATE= 100Hz'");
  if (unit_line == 0) f.fail(header_end, "UNIT", "missing header line 'UNIT  = gal'");

  std::array<Record, 3> out;
  for (int c = 0; c < 3; ++c) {
    out[c].name = (site.empty() ? file_stem(path) : "JMA " + site) + " " + names[c];
    out[c].source = path + " (JMA CSV" + (initial.empty() ? "" : ", initial time " + initial) + ")";
    out[c].dt = 1.0 / rate;
  }
  std::vector<double> row;
  for (; i < f.lines.size(); ++i) {
    const long ln = long(i) + 1;
    const std::string& line = f.lines[i];
    if (is_blank(line)) continue;
    row.clear();
    std::size_t p = 0;
    for (int k = 0; p <= line.size(); ++k) {
      std::size_t e = line.find(',', p);
      if (e == std::string::npos) e = line.size();
      const std::string cell = line.substr(p, e - p);
      p = e + 1;
      if (k >= 3) {
        if (is_blank(cell)) continue;  // trailing comma
        f.fail(ln, "NS,EW,UD", "expected 3 values, found more: '" + excerpt(line) + "'");
      }
      std::vector<double> v;
      const LineParse r = parse_numbers(cell, v);
      const char* field = "NS";
      for (int c = 0; c < 3; ++c)
        if (column_of[c] == k) field = names[c];
      if (r.status != LineParse::ok) fail_parse(f, ln, field, r);
      if (v.size() != 1) f.fail(ln, field, "expected one number, found '" + excerpt(cell) + "'");
      row.push_back(v[0]);
    }
    if (row.size() != 3)
      f.fail(ln, "NS,EW,UD", "expected 3 values, found " + std::to_string(row.size()));
    for (int c = 0; c < 3; ++c) {
      out[c].acc.push_back(row[column_of[c]]);
      scale_samples(f, ln, out[c].acc, out[c].acc.size() - 1, factor, names[c]);
    }
  }
  if (out[0].acc.empty()) f.fail(long(f.lines.size()), "samples", "no samples after the header");
  if (out[0].acc.size() < 2) f.fail(long(f.lines.size()), "samples", "a record needs at least 2 samples after the header");
  return out;
}

// Plain numbers: (time, acceleration) per line, or bare values opt.dt apart (any count per line).
// Lines starting with '#' or ';' are comments; opt.skip_lines raw lines at the top are ignored (for
// a numeric line that is not data, like the "0.02 0.50" of some Japanese files). Times must
// increase with a uniform step (a record here is uniformly sampled); the first time becomes t0.
[[nodiscard]] inline Record read_columns(const std::string& path, const ReadOptions& opt = {}) {
  using namespace detail::gm;
  if (opt.skip_lines < 0) throw InputError("read_columns: skip_lines must be >= 0");
  if (opt.dt < 0 || !std::isfinite(opt.dt)) throw InputError("read_columns: dt must be >= 0");
  const TextFile f = read_text(path);
  const Layout layout = opt.layout != Layout::automatic ? opt.layout : (opt.dt > 0 ? Layout::values : Layout::time_value);
  if (layout == Layout::values && !(opt.dt > 0))
    throw InputError("read_columns: Layout::values needs ReadOptions::dt > 0");

  const double factor = unit_factor(opt.unit);
  Record r;
  r.name = file_stem(path);
  r.source = path + " (columns)";
  std::vector<double> times, pair;
  std::vector<long> time_lines;
  long last_ln = 0;
  for (std::size_t i = static_cast<std::size_t>(opt.skip_lines); i < f.lines.size(); ++i) {
    const long ln = long(i) + 1;
    if (is_blank(f.lines[i]) || is_comment(f.lines[i])) continue;
    last_ln = ln;
    if (layout == Layout::values) {
      const std::size_t before = r.acc.size();
      parse_samples(f, ln, r.acc);
      scale_samples(f, ln, r.acc, before, factor);
      continue;
    }
    pair.clear();
    const LineParse p = parse_numbers(f.lines[i], pair);
    if (p.status != LineParse::ok) fail_parse(f, ln, p.index == 0 ? "time" : "acceleration", p);
    if (pair.size() == 1)
      f.fail(ln, "columns", "one value per line: give ReadOptions::dt (the sample spacing) for a single-column file");
    if (pair.size() != 2)
      f.fail(ln, "columns", "expected 2 columns (time, acceleration), found " + std::to_string(pair.size()));
    if (!times.empty() && !(pair[0] > times.back()))
      f.fail(ln, "time", "time " + num(pair[0]) + " s is not greater than the previous " + num(times.back()) +
                             " s (line " + std::to_string(time_lines.back()) + ")");
    times.push_back(pair[0]);
    time_lines.push_back(ln);
    r.acc.push_back(pair[1]);
    scale_samples(f, ln, r.acc, r.acc.size() - 1, factor, "acceleration");
  }
  if (r.acc.empty()) f.fail(last_ln > 0 ? last_ln : long(f.lines.size()), "samples", "no samples");
  if (layout == Layout::values) {
    // The spacing comes from the caller: as plausible as a header's, and two samples at least (one
    // sample, or dt = 1e-300 or 1e300, ran before: issue 13).
    if (const std::string why = record_dt_problem(opt.dt); !why.empty()) f.fail(0, "dt", why);
    if (r.acc.size() < 2) f.fail(last_ln, "samples", "a record needs at least 2 samples");
    r.dt = opt.dt;
  } else {
    if (times.size() < 2) f.fail(last_ln, "time", "a (time, acceleration) file needs 2 samples to give dt");
    // Every step must match the median step (a gap or a repeated block shows up where it is, which
    // a comparison with the mean step would not); dt is then the mean step, the most precise.
    std::vector<double> steps(times.size() - 1);
    for (std::size_t k = 1; k < times.size(); ++k) steps[k - 1] = times[k] - times[k - 1];
    std::vector<double> sorted = steps;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t k = 0; k < steps.size(); ++k)
      if (std::abs(steps[k] - median) > 0.01 * median)
        f.fail(time_lines[k + 1], "time", "time step not uniform: " + num(steps[k]) + " s after t = " +
                                              num(times[k]) + " s, the record's step is " + num(median) + " s");
    r.t0 = times.front();
    r.dt = (times.back() - times.front()) / double(times.size() - 1);
    if (const std::string why = record_dt_problem(r.dt); !why.empty()) f.fail(time_lines[1], "time", why);
  }
  return r;
}

// The format of a record file, from its content: "PEER" on line 1 (or a PEER NPTS line 4) -> AT2,
// "Scale Factor" -> K-NET, "SITE CODE" -> JMA CSV, numbers -> columns. Anything else is an
// InputError ("unknown format").
[[nodiscard]] inline Format detect_format(const std::string& path) {
  using namespace detail::gm;
  const TextFile f = read_text(path);
  std::string npts, dt;
  if (contains(upper(f.lines[0]), "PEER") || (f.lines.size() >= 4 && match_npts(f.lines[3], npts, dt)))
    return Format::peer_at2;
  const std::size_t scan = std::min<std::size_t>(f.lines.size(), 40);
  for (std::size_t i = 0; i < scan; ++i) {
    const std::string u = upper(f.lines[i]);
    if (contains(u, "SCALE FACTOR")) return Format::knet;
    if (contains(u, "SITE CODE")) return Format::jma_csv;
  }
  for (std::size_t i = 0; i < f.lines.size(); ++i) {
    if (is_blank(f.lines[i]) || is_comment(f.lines[i])) continue;
    std::vector<double> v;
    if (parse_numbers(f.lines[i], v).status == LineParse::ok) return Format::columns;
    f.fail(long(i) + 1, "format",
           "unknown record format: '" + excerpt(f.lines[i]) +
               "' is neither a PEER NGA AT2, K-NET/KiK-net or JMA CSV header nor a line of numbers");
  }
  f.fail(long(f.lines.size()), "format", "unknown record format: only comments");
}

// Reads one component; Format::automatic detects it. JMA CSV gives opt.component (0 NS, 1 EW, 2 UD).
[[nodiscard]] inline Record read_record(const std::string& path, Format format = Format::automatic,
                                        const ReadOptions& opt = {}) {
  if (format == Format::automatic) format = detect_format(path);
  switch (format) {
    case Format::peer_at2: return read_peer_at2(path);
    case Format::knet: return read_knet(path, opt.remove_mean);
    case Format::jma_csv: {
      if (opt.component < 0 || opt.component > 2)
        throw InputError("read_record: JMA component must be 0 (NS), 1 (EW) or 2 (UD)");
      auto c = read_jma_csv(path);
      return std::move(c[static_cast<std::size_t>(opt.component)]);
    }
    case Format::columns: return read_columns(path, opt);
    case Format::automatic: break;
  }
  throw InputError(path, 0, "format", "unknown record format");
}

// Writes "# name", "# source", "# dt", "# unit" comments and (time, m/s^2) pairs at full precision,
// so read_columns(path) gives the record back.
inline void write_columns(const std::string& path, const Record& r) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError(path, 0, "file", "cannot open for writing");
  auto one_line = [](std::string s) {
    for (char& c : s)
      if (c == '\n' || c == '\r') c = ' ';
    return s;
  };
  out << "# name: " << one_line(r.name) << "\n# source: " << one_line(r.source) << "\n";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", r.dt);
  out << "# dt: " << buf << " s, " << r.acc.size() << " samples\n# columns: time (s), acceleration (m/s^2)\n";
  for (std::size_t i = 0; i < r.acc.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g\n", r.time(i), r.acc[i]);
    out << buf;
  }
  out.flush();
  if (!out) throw InputError(path, 0, "file", "write failed");
}

}  // namespace furniture_fem
