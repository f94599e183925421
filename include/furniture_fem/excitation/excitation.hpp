#pragma once
// furniture_fem/excitation/excitation.hpp: the ground motion that drives the shake table.
//
// A Record is one component of acceleration, uniformly sampled; a TableMotion is the table's X (and
// optionally Y, Z) acceleration as a function of time, ready for Simulation::set_table_acceleration.
// Readers cover the formats strong-motion data come in (PEER NGA AT2, K-NET/KiK-net ASCII, JMA CSV,
// plain columns); processing covers what a record needs before it drives a model (resampling,
// baseline correction, zero-phase low-pass, windowing, integration); response spectra use the exact
// piecewise-linear recurrence; seeded synthetic motions are the toolkit's default input.
// Everything inside is SI: m/s^2, m/s, m, s. See docs/excitation/ground_motions.md.
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
#define FURNITURE_FEM_EXCITATION_INTERNAL
#include "detail/excitation_dsp.hpp"
#include "detail/excitation_text.hpp"
#undef FURNITURE_FEM_EXCITATION_INTERNAL

namespace furniture_fem {

inline constexpr double standard_gravity = 9.80665;  // m/s^2 per g (the PEER/NGA convention)

// ---------------------------------------------------------------------------------------------
// Records
// ---------------------------------------------------------------------------------------------

// One component of acceleration sampled every dt from t0: sample i is at t0 + i dt.
struct Record {
  std::string name;
  std::string source;
  double dt = 0.01;
  std::vector<double> acc;  // m/s^2
  double t0 = 0;

  [[nodiscard]] std::size_t size() const noexcept { return acc.size(); }
  // Time spanned by the samples, (n - 1) dt; the motion is zero outside [t0, t_end()].
  [[nodiscard]] double duration() const noexcept { return acc.size() > 1 ? dt * double(acc.size() - 1) : 0.0; }
  [[nodiscard]] double t_end() const noexcept { return t0 + duration(); }
  [[nodiscard]] double time(std::size_t i) const noexcept { return t0 + dt * double(i); }

  // Linear interpolation between samples, 0 outside the record. Called every time step of a
  // simulation, so it must not allocate.
  [[nodiscard]] double value_at(double t) const noexcept {
    const std::size_t n = acc.size();
    if (n == 0 || !(t >= t0)) return 0.0;  // also catches NaN t
    const double s = (t - t0) / dt;
    const double last = double(n - 1);
    if (s >= last) return s <= last + 1e-9 ? acc[n - 1] : 0.0;  // tolerate t_end() rounding
    const auto i = static_cast<std::size_t>(s);
    const double f = s - double(i);
    return acc[i] + f * (acc[i + 1] - acc[i]);
  }

  // Largest |acceleration| (the PGA of the component) and the time of its first occurrence.
  [[nodiscard]] double peak() const noexcept {
    double p = 0;
    for (double a : acc) p = std::max(p, std::abs(a));
    return p;
  }
  [[nodiscard]] double peak_time() const noexcept {
    std::size_t k = 0;
    for (std::size_t i = 1; i < acc.size(); ++i)
      if (std::abs(acc[i]) > std::abs(acc[k])) k = i;
    return time(k);
  }

  // The same record with every sample multiplied by factor (a test "level", e.g. 0.5 for 50 %).
  [[nodiscard]] Record scaled(double factor) const {
    Record r = *this;
    for (double& a : r.acc) a *= factor;
    return r;
  }
};

// One component of acceleration given by points (t_i, a_i) with strictly increasing times: linear in
// between, zero before the first and after the last (a scene file's "points" source). Exact at any
// time, where a Record would resample it.
struct PiecewiseLinear {
  std::vector<double> t, a;  // s, m/s^2

  // Throws InputError naming the component and the offending point: at least one point, finite
  // values, times strictly increasing.
  void check(const std::string& component) const {
    const auto fail = [&](const std::string& what) { throw InputError("TableMotion::from_points", 0, component, what); };
    if (t.empty() || t.size() != a.size()) fail("needs at least one point, with one acceleration per time");
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (!std::isfinite(t[i]) || !std::isfinite(a[i])) fail("point " + std::to_string(i) + " is not finite");
      if (i > 0 && !(t[i] > t[i - 1]))
        fail("times must increase strictly: point " + std::to_string(i) + " at " + text(t[i]) + " s follows " +
             text(t[i - 1]) + " s");
    }
  }
  static std::string text(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
  }
  // Called every time step: no allocation, a binary search.
  [[nodiscard]] double value_at(double time) const noexcept {
    if (t.empty() || !(time >= t.front()) || time > t.back()) return 0.0;  // also catches NaN
    const auto hi = std::upper_bound(t.begin(), t.end(), time);
    if (hi == t.end()) return a.back();
    const std::size_t i = static_cast<std::size_t>(hi - t.begin()) - 1;
    const double f = (time - t[i]) / (t[i + 1] - t[i]);
    return a[i] + f * (a[i + 1] - a[i]);
  }
  [[nodiscard]] double peak() const noexcept {
    double p = 0;
    for (double v : a) p = std::max(p, std::abs(v));
    return p;
  }
  [[nodiscard]] double t_end() const noexcept { return t.empty() ? 0.0 : t.back(); }
  [[nodiscard]] PiecewiseLinear scaled(double factor) const {
    PiecewiseLinear p = *this;
    for (double& v : p.a) v *= factor;
    return p;
  }
};

// Acceleration of the shake table: X always, Y and Z when has_y / has_z (a 1-D table moves in X).
struct TableMotion {
  Record x, y, z;
  bool has_y = false, has_z = false;
  // Set by from_points: the components as given (x, y, z then stay empty); `at` reads them.
  std::vector<PiecewiseLinear> points = {};

  [[nodiscard]] static TableMotion one_d(Record x) { return TableMotion{std::move(x), {}, {}, false, false}; }
  [[nodiscard]] static TableMotion three_d(Record x, Record y, Record z) {
    return TableMotion{std::move(x), std::move(y), std::move(z), true, true};
  }
  // A motion given by points per component (an empty y or z: that component is zero). Throws
  // InputError if a component's points are not valid (PiecewiseLinear::check).
  [[nodiscard]] static TableMotion from_points(PiecewiseLinear px, PiecewiseLinear py = {}, PiecewiseLinear pz = {}) {
    TableMotion m;
    px.check("x");
    m.has_y = !py.t.empty();
    m.has_z = !pz.t.empty();
    if (m.has_y) py.check("y");
    if (m.has_z) pz.check("z");
    m.points = {std::move(px), std::move(py), std::move(pz)};
    return m;
  }

  [[nodiscard]] Eigen::Vector3d at(double t) const noexcept {
    if (!points.empty()) return {points[0].value_at(t), points[1].value_at(t), points[2].value_at(t)};
    return Eigen::Vector3d(x.value_at(t), has_y ? y.value_at(t) : 0.0, has_z ? z.value_at(t) : 0.0);
  }
  // Largest |acceleration| of each component (m/s^2).
  [[nodiscard]] Eigen::Vector3d peaks() const noexcept {
    if (!points.empty()) return {points[0].peak(), points[1].peak(), points[2].peak()};
    return {x.peak(), has_y ? y.peak() : 0.0, has_z ? z.peak() : 0.0};
  }
  // So a TableMotion can be passed straight to Simulation::set_table_acceleration.
  Eigen::Vector3d operator()(double t) const noexcept { return at(t); }

  [[nodiscard]] bool is_3d() const noexcept { return has_y || has_z; }
  // Time of the last sample of any component.
  [[nodiscard]] double t_end() const noexcept {
    if (!points.empty()) return std::max({points[0].t_end(), points[1].t_end(), points[2].t_end()});
    double e = x.t_end();
    if (has_y) e = std::max(e, y.t_end());
    if (has_z) e = std::max(e, z.t_end());
    return e;
  }
  // All components multiplied by level (shake-table tests are run at 25 %, 50 %, 100 % ...).
  [[nodiscard]] TableMotion scaled(double level) const {
    TableMotion m{x.scaled(level), y.scaled(level), z.scaled(level), has_y, has_z};
    for (const auto& p : points) m.points.push_back(p.scaled(level));
    return m;
  }
};

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

// ---------------------------------------------------------------------------------------------
// Processing
// ---------------------------------------------------------------------------------------------

// Linear interpolation onto a new step over the same time span (the last sample may be dropped
// when the span is not a multiple of dt). Down-sampling does not low-pass: call low_pass first.
inline constexpr double max_resampled = 1e9;  // samples (8 GB)
[[nodiscard]] inline Record resample(const Record& rec, double dt) {
  detail::gm::check_record(rec, "resample");
  if (!(dt > 0) || !std::isfinite(dt)) throw InputError("resample: dt must be positive");
  Record r = rec;
  r.dt = dt;
  const double samples = std::floor(rec.duration() / dt + 1e-6) + 1;
  if (!(samples <= max_resampled))
    throw InputError("resample: dt = " + detail::gm::num(dt) + " s over " + detail::gm::num(rec.duration()) +
                     " s gives " + detail::gm::num(samples) + " samples (at most 1e9)");
  const auto n = static_cast<std::size_t>(samples);
  r.acc.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.acc[i] = rec.value_at(rec.t0 + double(i) * dt);
  return r;
}

// Removes the least-squares polynomial of order 0 (mean), 1 (linear) or 2 (quadratic) from the
// acceleration: a base-line error in acceleration becomes a drift in velocity and displacement.
// With zero_final_velocity a constant is then subtracted so the velocity (trapezoid) ends at 0.
[[nodiscard]] inline Record baseline_correct(const Record& rec, int order = 1, bool zero_final_velocity = false) {
  detail::gm::check_record(rec, "baseline_correct");
  if (order < 0 || order > 2) throw InputError("baseline_correct: order must be 0, 1 or 2");
  Record r = rec;
  detail::gm::remove_polynomial(r.acc, order);
  if (zero_final_velocity && r.acc.size() > 1) {
    double v = 0;
    for (std::size_t i = 1; i < r.acc.size(); ++i) v += 0.5 * r.dt * (r.acc[i - 1] + r.acc[i]);
    const double c = v / r.duration();  // the trapezoid weights of a constant sum to the duration
    for (double& a : r.acc) a -= c;
  }
  return r;
}

// Zero-phase Butterworth low-pass: the cascade of second-order sections run forward, then backward,
// so the gain is |H|^2 (-6 dB at f_cut, order doubled) and nothing is shifted in time. The ends are
// padded by odd reflection over three periods of f_cut to keep edge transients out.
[[nodiscard]] inline Record low_pass(const Record& rec, double f_cut, int order = 4) {
  detail::gm::check_record(rec, "low_pass");
  if (order < 1 || order > 16) throw InputError("low_pass: order must be 1..16");
  if (!(f_cut > 0) || !(f_cut < 0.5 / rec.dt))
    throw InputError("low_pass: f_cut = " + detail::gm::num(f_cut) + " Hz must lie in (0, Nyquist = " +
                                detail::gm::num(0.5 / rec.dt) + " Hz)");
  const auto sections = detail::gm::butterworth_lowpass(order, f_cut, rec.dt);
  const std::size_t n = rec.acc.size();
  // Compared as doubles first: 3 / (f dt) overflows size_t for a tiny dt (undefined; found by fuzzing).
  const double periods = std::ceil(3.0 / (f_cut * rec.dt));
  const std::size_t pad = periods < double(n - 1) ? static_cast<std::size_t>(periods) : n - 1;
  std::vector<double> x(n + 2 * pad);
  for (std::size_t k = 0; k < pad; ++k) {
    x[pad - 1 - k] = 2.0 * rec.acc[0] - rec.acc[k + 1];
    x[pad + n + k] = 2.0 * rec.acc[n - 1] - rec.acc[n - 2 - k];
  }
  std::copy(rec.acc.begin(), rec.acc.end(), x.begin() + static_cast<std::ptrdiff_t>(pad));
  for (const auto& s : sections) detail::gm::run_section(s, x);
  std::reverse(x.begin(), x.end());
  for (const auto& s : sections) detail::gm::run_section(s, x);
  std::reverse(x.begin(), x.end());
  Record r = rec;
  std::copy(x.begin() + static_cast<std::ptrdiff_t>(pad), x.begin() + static_cast<std::ptrdiff_t>(pad + n),
            r.acc.begin());
  return r;
}

// The samples in [t_start, t_end] (t0 becomes the first kept sample's time), with a cosine
// (half-Hann) taper over taper_seconds at each end so the cut does not jerk the table. The taper
// is limited to half the window.
[[nodiscard]] inline Record window(const Record& rec, double t_start, double t_end, double taper_seconds = 0) {
  detail::gm::check_record(rec, "window");
  // Named with the record and its file: a scene's window that starts after its record ends lands here.
  if (!(t_end >= t_start))
    throw InputError("window: t_start = " + detail::gm::num(t_start) + " s is after t_end = " + detail::gm::num(t_end) +
                     " s; record '" + rec.name + "' (" + rec.source + ") spans [" + detail::gm::num(rec.t0) + ", " +
                     detail::gm::num(rec.t_end()) + "] s");
  if (!(taper_seconds >= 0)) throw InputError("window: taper_seconds must be >= 0");
  const double eps = 1e-6 * rec.dt;
  // A sample within 1e-6 dt of a bound counts as inside (t / dt is rarely an exact integer).
  const double first = std::max(0.0, std::ceil((t_start - rec.t0) / rec.dt - 1e-6));
  const double last = std::min(double(rec.acc.size() - 1), std::floor((t_end - rec.t0) / rec.dt + 1e-6));
  if (!(last >= first) || rec.time(static_cast<std::size_t>(first)) > t_end + eps)
    throw InputError("window: no sample of '" + rec.name + "' in [" + detail::gm::num(t_start) + ", " +
                                detail::gm::num(t_end) + "] s");
  const auto i0 = static_cast<std::size_t>(first), i1 = static_cast<std::size_t>(last);
  Record r = rec;
  r.acc.assign(rec.acc.begin() + static_cast<std::ptrdiff_t>(i0), rec.acc.begin() + static_cast<std::ptrdiff_t>(i1 + 1));
  r.t0 = rec.time(i0);
  const double span = r.duration();
  const double taper = std::min(taper_seconds, 0.5 * span);
  if (taper > 0)
    for (std::size_t i = 0; i < r.acc.size(); ++i) {
      const double t = double(i) * r.dt, d = std::min(t, span - t);
      if (d < taper) r.acc[i] *= 0.5 * (1.0 - std::cos(detail::gm::kPi * d / taper));
    }
  return r;
}

// Acceleration with its velocity and displacement (trapezoid rule, from rest unless v0, d0 given).
struct Kinematics {
  double dt = 0, t0 = 0;
  std::vector<double> acc, vel, disp;
};

[[nodiscard]] inline Kinematics integrate(const Record& rec, double v0 = 0, double d0 = 0) {
  detail::gm::check_record(rec, "integrate");
  Kinematics k{rec.dt, rec.t0, rec.acc, {}, {}};
  const std::size_t n = rec.acc.size();
  k.vel.resize(n);
  k.disp.resize(n);
  k.vel[0] = v0;
  k.disp[0] = d0;
  for (std::size_t i = 1; i < n; ++i) {
    k.vel[i] = k.vel[i - 1] + 0.5 * rec.dt * (rec.acc[i - 1] + rec.acc[i]);
    k.disp[i] = k.disp[i - 1] + 0.5 * rec.dt * (k.vel[i - 1] + k.vel[i]);
  }
  return k;
}

// ---------------------------------------------------------------------------------------------
// Response spectra
// ---------------------------------------------------------------------------------------------

// Peak responses of elastic SDOF oscillators u'' + 2 zeta w u' + w^2 u = -a_g(t), w = 2 pi / T.
struct Spectrum {
  double zeta = 0.05;
  std::vector<double> periods;  // s
  std::vector<double> sd;       // max |u|, m
  std::vector<double> sv;       // max |u'| (relative velocity), m/s
  std::vector<double> psv;      // pseudo-velocity w Sd, m/s
  std::vector<double> psa;      // pseudo-acceleration w^2 Sd, m/s^2
  std::vector<double> sa;       // max |u'' + a_g| (true absolute acceleration), m/s^2
};

// n periods evenly spaced in log from t_min to t_max (both included).
[[nodiscard]] inline std::vector<double> log_periods(double t_min, double t_max, int n) {
  if (!(t_min > 0) || !(t_max > t_min) || n < 2)
    throw InputError("log_periods: need 0 < t_min < t_max and n >= 2");
  std::vector<double> p(static_cast<std::size_t>(n));
  const double r = std::log(t_max / t_min) / double(n - 1);
  for (int i = 0; i < n; ++i) p[static_cast<std::size_t>(i)] = t_min * std::exp(r * double(i));
  p.back() = t_max;
  return p;
}

// Exact for the piecewise-linear input of value_at (Nigam & Jennings 1969): each sample interval is
// cut into substeps of at most T/100 (the input stays linear in each) only so the peak is not missed
// between samples; sampling a peak at that spacing errs by at most (pi/100)^2 / 2 = 0.05 %. The oscillator starts at rest; the record is followed by a ramp to zero over one
// dt and one period of free vibration, where the peak of a short pulse may occur.
[[nodiscard]] inline Spectrum response_spectrum(const Record& rec, std::vector<double> periods, double zeta = 0.05) {
  detail::gm::check_record(rec, "response_spectrum");
  if (!(zeta >= 0 && zeta < 1)) throw InputError("response_spectrum: zeta must lie in [0, 1)");
  Spectrum s;
  s.zeta = zeta;
  const std::size_t m = periods.size();
  s.sd.resize(m);
  s.sv.resize(m);
  s.psv.resize(m);
  s.psa.resize(m);
  s.sa.resize(m);
  for (std::size_t p = 0; p < m; ++p) {
    const double T = periods[p];
    if (!(T > 0) || !std::isfinite(T)) throw InputError("response_spectrum: periods must be positive");
    const double w = 2.0 * detail::gm::kPi / T;
    // Substeps per sample and free-vibration steps, checked before they become integers.
    const double subs = std::max(0.0, rec.dt / (T / 100.0) - 1e-9);
    if (!count_fits(subs, 1e6))
      throw InputError("response_spectrum: period " + detail::gm::num(T) + " s is too short for the record's dt " +
                       detail::gm::num(rec.dt) + " s (" + detail::gm::num(subs) + " substeps per sample; at most 1e6)");
    const int sub = std::max(1, static_cast<int>(std::ceil(subs)));
    const double h = rec.dt / sub;
    if (!count_fits(T / h, 1e9))
      throw InputError("response_spectrum: period " + detail::gm::num(T) + " s is too long for the record's dt " +
                       detail::gm::num(rec.dt) + " s (" + detail::gm::num(T / h) + " steps of free vibration; at most 1e9)");
    const detail::gm::SdofStep step(w, zeta, h);
    double u = 0, v = 0, umax = 0, vmax = 0, amax = 0;  // starts at rest
    auto track = [&] {
      umax = std::max(umax, std::abs(u));
      vmax = std::max(vmax, std::abs(v));
      amax = std::max(amax, std::abs(2.0 * zeta * w * v + w * w * u));
    };
    // One sample interval from a0 to a1 in `sub` linear pieces.
    auto interval = [&](double a0, double a1) {
      for (int j = 0; j < sub; ++j) {
        const double f0 = double(j) / sub, f1 = double(j + 1) / sub;
        step.advance(u, v, a0 + (a1 - a0) * f0, a0 + (a1 - a0) * f1);
        track();
      }
    };
    for (std::size_t i = 0; i + 1 < rec.acc.size(); ++i) interval(rec.acc[i], rec.acc[i + 1]);
    interval(rec.acc.back(), 0.0);
    const auto free_steps = static_cast<long>(std::ceil(T / h));
    for (long k = 0; k < free_steps; ++k) {
      step.advance(u, v, 0.0, 0.0);
      track();
    }
    s.sd[p] = umax;
    s.sv[p] = vmax;
    s.psv[p] = w * umax;
    s.psa[p] = w * w * umax;
    s.sa[p] = amax;
  }
  s.periods = std::move(periods);
  return s;
}

// ---------------------------------------------------------------------------------------------
// Synthetic motions
// ---------------------------------------------------------------------------------------------

// Jennings-type intensity envelope: (t / rise)^2 build-up, a constant strong phase, an exponential
// coda exp(-decay (t - rise - strong)), and a cosine taper to exactly zero over the last end_taper
// seconds so the table stops without a jump.
struct Envelope {
  double rise = 1.5;       // s
  double strong = 3.5;     // s
  double decay = 0.6;      // 1/s
  double end_taper = 0.5;  // s

  [[nodiscard]] double operator()(double t, double duration) const noexcept {
    if (t < 0 || t > duration) return 0.0;
    double e = 1.0;
    if (t < rise)
      e = (t / rise) * (t / rise);
    else if (t > rise + strong)
      e = std::exp(-decay * (t - rise - strong));
    const double left = duration - t;
    if (end_taper > 0 && left < end_taper) e *= 0.5 * (1.0 - std::cos(detail::gm::kPi * left / end_taper));
    return e;
  }
};

struct SyntheticOptions {
  std::uint64_t seed = 1;
  double duration = 10.0;           // s
  double dt = 0.01;                 // s
  double pga = 8.0;                 // m/s^2, the peak of the result
  double predominant_period = 0.5;  // s, where the Kanai-Tajimi (Fourier power) spectrum peaks
  Envelope envelope{};
  double omega_g = 0;               // rad/s, Kanai-Tajimi ground frequency; 0: from predominant_period
  // Kanai-Tajimi ground damping. 0.3 gives a clear predominant period, the 5 % PSA spectrum peaking
  // near it as in JMA Kobe; Kanai's firm-ground 0.6 gives a broad plateau at 0.5-0.8 of it.
  double zeta_g = 0.3;
  // Clough-Penzien second filter, a high-pass at omega_f = omega_f_ratio * omega_g: the Kanai-Tajimi
  // spectrum stays flat down to 0 Hz, which gives table displacements of ~0.7 m at 8 m/s^2; at 0.2
  // the mean PGV/PGD at 8 m/s^2 and 0.5 s (0.77 m/s, 0.28 m) are near JMA Kobe NS's (0.91 m/s,
  // 0.21 m). 0: pure Kanai-Tajimi.
  double omega_f_ratio = 0.2;
  double zeta_f = 0.6;
  std::string name;                 // empty: "synthetic (seed N)"
};

// Gaussian white noise (Box-Muller on mt19937_64, so a seed gives the same samples everywhere)
// through a Kanai-Tajimi filter (and the Clough-Penzien high-pass), times the envelope, corrected so
// the table ends at rest where it started, scaled to the PGA. The correction subtracts e(t) (c0 + c1 t), which keeps the motion zero
// where the envelope is and makes the final velocity and displacement (trapezoid) zero.
[[nodiscard]] inline Record synthetic_motion(const SyntheticOptions& o = {}) {
  using detail::gm::kPi;
  if (!(o.dt > 0) || !(o.duration >= 2 * o.dt) || !std::isfinite(o.duration))
    throw InputError("synthetic_motion: need dt > 0 and duration >= 2 dt");
  if (!(o.pga > 0)) throw InputError("synthetic_motion: pga must be positive");
  if (!(o.zeta_g > 0 && o.zeta_g < 1)) throw InputError("synthetic_motion: zeta_g must lie in (0, 1)");
  if (o.omega_f_ratio > 0 && !(o.zeta_f > 0 && o.zeta_f < 1))
    throw InputError("synthetic_motion: zeta_f must lie in (0, 1)");
  double wg = o.omega_g;
  if (!(wg > 0)) {
    if (!(o.predominant_period > 0))
      throw InputError("synthetic_motion: predominant_period (or omega_g) must be positive");
    // The Kanai-Tajimi spectrum (1 + 4 z^2 r^2) / ((1 - r^2)^2 + 4 z^2 r^2), r = w / wg, peaks at
    // r^2 = 2 / (1 + sqrt(1 + 8 z^2)), below wg for a damped ground.
    const double r2 = 2.0 / (1.0 + std::sqrt(1.0 + 8.0 * o.zeta_g * o.zeta_g));
    wg = 2.0 * kPi / o.predominant_period / std::sqrt(r2);
  }
  if (!(wg * o.dt < kPi)) throw InputError("synthetic_motion: dt too coarse for the ground frequency");

  if (!count_fits(o.duration / o.dt, 1e9))
    throw InputError("synthetic_motion: duration " + detail::gm::num(o.duration) + " s is " + detail::gm::num(o.duration / o.dt) +
                     " samples of dt " + detail::gm::num(o.dt) + " s (at most 1e9)");
  const auto n = static_cast<std::size_t>(std::llround(o.duration / o.dt)) + 1;
  const double T = o.dt * double(n - 1);
  // Run the filters through a warm-up of 5 time constants so the noise is stationary when the
  // envelope starts.
  const double wf = o.omega_f_ratio > 0 ? o.omega_f_ratio * wg : 0.0;
  const double settle = std::max({1.0, 5.0 / (o.zeta_g * wg), wf > 0 ? 5.0 / (o.zeta_f * wf) : 0.0});
  if (!count_fits(settle / o.dt, 1e9))
    throw InputError("synthetic_motion: the filters' warm-up of " + detail::gm::num(settle) + " s is " +
                     detail::gm::num(settle / o.dt) + " samples of dt " + detail::gm::num(o.dt) +
                     " s (at most 1e9): zeta_g or the ground frequency is too small");
  const auto warm = static_cast<std::size_t>(std::ceil(settle / o.dt));
  detail::gm::NormalSource noise(o.seed);
  const detail::gm::SdofStep step(wg, o.zeta_g, o.dt);
  const detail::gm::SdofStep high(wf > 0 ? wf : 1.0, o.zeta_f, o.dt);
  std::vector<double> a(n), e(n), et(n);
  double u = 0, v = 0, uf = 0, vf = 0, w0 = noise(), g0 = 0;
  for (std::size_t k = 1; k < warm + n; ++k) {
    const double w1 = noise();
    step.advance(u, v, w0, w1);
    w0 = w1;
    double g1 = -(2.0 * o.zeta_g * wg * v + wg * wg * u);  // absolute acceleration of the Kanai-Tajimi "ground"
    if (wf > 0) {
      // Relative acceleration of the second oscillator driven by g: the high-pass ratio r^2 / (...)
      high.advance(uf, vf, g0, g1);
      g0 = g1;
      g1 = -g1 - 2.0 * o.zeta_f * wf * vf - wf * wf * uf;
    }
    if (k >= warm) {
      const std::size_t i = k - warm;
      const double t = o.dt * double(i);
      e[i] = o.envelope(t, T);
      et[i] = e[i] * t;
      a[i] = g1 * e[i];
    }
  }
  // Final velocity and displacement of the trapezoid integration, both linear in the samples.
  auto ends = [&](const std::vector<double>& x, double& vT, double& dT) {
    double vel = 0, d = 0;
    for (std::size_t i = 1; i < n; ++i) {
      const double vn = vel + 0.5 * o.dt * (x[i - 1] + x[i]);
      d += 0.5 * o.dt * (vel + vn);
      vel = vn;
    }
    vT = vel;
    dT = d;
  };
  double va, da, ve, de, vt, dtt;
  ends(a, va, da);
  ends(e, ve, de);
  ends(et, vt, dtt);
  const double det = ve * dtt - vt * de;
  if (std::abs(det) > 0) {
    const double c0 = (va * dtt - vt * da) / det, c1 = (ve * da - va * de) / det;
    for (std::size_t i = 0; i < n; ++i) a[i] -= c0 * e[i] + c1 * et[i];
  }
  double peak = 0;
  for (double x : a) peak = std::max(peak, std::abs(x));
  if (!(peak > 0)) throw InputError("synthetic_motion: the envelope is zero everywhere");
  for (double& x : a) x *= o.pga / peak;

  Record r;
  r.name = o.name.empty() ? "synthetic (seed " + std::to_string(o.seed) + ")" : o.name;
  r.source = "furniture_fem synthetic: Kanai-Tajimi omega_g " + detail::gm::num(wg) + " rad/s, zeta_g " +
             detail::gm::num(o.zeta_g) + ", seed " + std::to_string(o.seed);
  r.dt = o.dt;
  r.acc = std::move(a);
  return r;
}

struct PulseOptions {
  double gamma = 2.0;     // oscillation parameter (> 1): the pulse lasts gamma Tp
  double nu = 0.0;        // phase, rad; 0: symmetric, velocity peak = amplitude at t_peak
  double t_peak = 0;      // s, centre of the pulse; 0: gamma Tp / 2 (the pulse starts at t = 0)
  double duration = 0;    // s; 0: until 1 s after the pulse
  double dt = 0.01;       // s
};

// Near-fault velocity pulse of Mavroeidis & Papageorgiou (2003),
//   v(t) = A/2 (1 + cos(2 pi fp tau / gamma)) cos(2 pi fp tau + nu),  |tau| <= gamma / (2 fp),
// tau = t - t_peak, fp = 1/Tp, A = amplitude (m/s); the record is its exact derivative (m/s^2).
[[nodiscard]] inline Record near_fault_pulse(double Tp, double amplitude, const PulseOptions& o = {}) {
  using detail::gm::kPi;
  if (!(Tp > 0)) throw InputError("near_fault_pulse: Tp must be positive");
  if (!(o.gamma > 1)) throw InputError("near_fault_pulse: gamma must be > 1");
  if (!(o.dt > 0)) throw InputError("near_fault_pulse: dt must be positive");
  const double fp = 1.0 / Tp, half = 0.5 * o.gamma * Tp;
  const double tc = o.t_peak > 0 ? o.t_peak : half;
  const double dur = o.duration > 0 ? o.duration : tc + half + 1.0;
  if (!count_fits(dur / o.dt, 1e9))
    throw InputError("near_fault_pulse: duration " + detail::gm::num(dur) + " s is " + detail::gm::num(dur / o.dt) +
                     " samples of dt " + detail::gm::num(o.dt) + " s (at most 1e9)");
  const auto n = static_cast<std::size_t>(std::llround(dur / o.dt)) + 1;
  Record r;
  r.name = "Mavroeidis-Papageorgiou pulse Tp " + detail::gm::num(Tp) + " s";
  r.source = "furniture_fem near_fault_pulse: A " + detail::gm::num(amplitude) + " m/s, gamma " +
             detail::gm::num(o.gamma) + ", nu " + detail::gm::num(o.nu);
  r.dt = o.dt;
  r.acc.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = o.dt * double(i) - tc;
    if (std::abs(tau) > half) continue;
    const double al = 2.0 * kPi * fp * tau / o.gamma, be = 2.0 * kPi * fp * tau + o.nu;
    r.acc[i] = -amplitude * kPi * fp / o.gamma *
               (std::sin(al) * std::cos(be) + o.gamma * (1.0 + std::cos(al)) * std::sin(be));
  }
  return r;
}

// The toolkit's default 3-D input: three independent synthetic components, `duration` s (10 by
// default) at dt 0.01, with the character of JMA Kobe 1995 (X 8 m/s^2 at 0.5 s, Y 6 m/s^2 at 0.6 s,
// Z 3.3 m/s^2 at 0.2 s).
[[nodiscard]] inline TableMotion default_table_motion(std::uint64_t seed = 1, double duration = 10.0) {
  const std::uint64_t base = detail::gm::splitmix64(seed);
  auto component = [&](std::uint64_t k, double pga, double period, const char* axis) {
    SyntheticOptions o;
    o.seed = detail::gm::splitmix64(base + k);
    o.pga = pga;
    o.predominant_period = period;
    o.duration = duration;
    o.name = std::string("default ") + axis + " (seed " + std::to_string(seed) + ")";
    return synthetic_motion(o);
  };
  return TableMotion::three_d(component(1, 8.0, 0.5, "X"), component(2, 6.0, 0.6, "Y"), component(3, 3.3, 0.2, "Z"));
}

}  // namespace furniture_fem
