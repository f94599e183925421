#pragma once
// furniture_fem/scene/scene_motion.hpp: the table's acceleration a scene asks for, without the model:
//
//   scene_ground_motion   the ground's: a record read, checked, windowed, filtered and scaled (or the
//                         synthetic motion, or points)
//   scene_table_motion    the table's: the ground's, or on a building's storey that floor's
//   motion_end            when the motion ends
//
// Light (no solver, no contact detection): the observers read the ground under a storey through it.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../core/errors.hpp"
#include "../excitation/excitation.hpp"
#include "../excitation/known_records.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/scene_building.hpp"
#include "detail/scene_names.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

namespace detail {

// The unit a record's numbers are read in, for messages: the scene's `units` (a column file; gal when
// not given) or what the format states (K-NET and JMA CSV: gal; AT2: its header line, g as a rule).
inline std::optional<Unit> declared_unit(const GroundMotionSpec& g) {
  switch (g.format) {
    case RecordFormat::columns:
      if (!g.units) return Unit::gal;
      return *g.units == AccelerationUnits::g ? Unit::g : *g.units == AccelerationUnits::gal ? Unit::gal : Unit::m_s2;
    case RecordFormat::knet:
    case RecordFormat::jma_csv: return Unit::gal;
    case RecordFormat::at2: return std::nullopt;  // the header says which (G, CM/S/S or M/S/S)
  }
  return std::nullopt;
}

inline const char* unit_text(Unit u) {
  switch (u) {
    case Unit::g: return "g";
    case Unit::gal: return "gal (cm/s^2)";
    case Unit::m_s2: return "m/s^2";
  }
  return "";
}
inline const char* unit_key_value(Unit u) { return u == Unit::g ? "g" : u == Unit::gal ? "gal" : "m/s2"; }

// A record's peak acceleration against the plausible band [plausible_pga_min_g, plausible_pga_max_g]
// (GroundMotionSpec::check_pga), right after reading (unit converted, before window, filter and
// scaling). Outside it: an InputError naming the record, its peak, the declared unit, the likely
// mistake (of the units that bring the peak inside the band, the one nearest 0.3 g: a strong record,
// what a furniture study runs) and the key to set.
inline void check_record_pga(const SceneSpec& s, const Record& r, const std::string& file_key) {
  const GroundMotionSpec& g = s.ground_motion;
  if (!g.check_pga) return;
  const double peak_g = r.peak() / standard_gravity;
  if (peak_g >= plausible_pga_min_g && peak_g <= plausible_pga_max_g) return;
  const std::optional<Unit> declared = declared_unit(g);
  // The unit the numbers are probably in: read in `from` they give peak_g; in `to`, peak_g * f(to) / f(from).
  std::optional<Unit> likely, read_as;
  double best = std::numeric_limits<double>::infinity();
  for (Unit from : {Unit::g, Unit::gal, Unit::m_s2}) {
    if (declared && from != *declared) continue;
    for (Unit to : {Unit::g, Unit::gal, Unit::m_s2}) {
      if (to == from) continue;
      const double p = peak_g * unit_factor(to) / unit_factor(from);
      if (!(p >= plausible_pga_min_g && p <= plausible_pga_max_g)) continue;
      const double distance = std::abs(std::log(p / 0.3));
      if (distance < best) best = distance, likely = to, read_as = from;
    }
  }
  const bool columns = g.format == RecordFormat::columns;
  const std::string unit_said =
      columns ? (g.units ? std::string("\"units\": \"") + unit_key_value(*declared) + "\""
                         : std::string("gal, the default of format \"columns\" (no \"units\" given)"))
              : "the unit of format \"" + enum_name(format_names, g.format) + "\"" +
                    (declared ? std::string(" (") + unit_text(*declared) + ")" : std::string(" (its header line 3)"));
  std::string message = "record '" + r.name + "' (" + r.source + ") peaks at " + fmt(peak_g) + " g (" +
                        fmt(r.peak()) + " m/s^2) read in " + unit_said + ", outside the plausible band [" +
                        fmt(plausible_pga_min_g) + ", " + fmt(plausible_pga_max_g) + "] g";
  if (likely) {
    message += ": the record is probably in " + std::string(unit_text(*likely)) + ", read as " + unit_text(*read_as);
    message += columns ? std::string("; set \"units\": \"") + unit_key_value(*likely) + "\""
                       : std::string("; correct the file's unit (format \"") + enum_name(format_names, g.format) +
                             "\" states its own), or write it as a column file with \"units\": \"" +
                             unit_key_value(*likely) + "\"";
  } else if (!(r.peak() > 0)) {
    message += ": the record is zero everywhere";
  } else {
    message += ": no unit (g, gal, m/s2) brings it into the band";
  }
  message += " (\"check_pga\": false runs it as given)";
  throw InputError(s.source, 0, columns ? "ground_motion.units" : file_key, message);
}

inline Record scene_record(const SceneSpec& s, const std::string& file, const char* axis) {
  const auto& g = s.ground_motion;
  const std::string path = s.resolve(file);
  const std::string key = std::string("ground_motion.files.") + axis;
  if (path.empty()) throw InputError(s.source, 0, key, "no record file given for this axis");
  if (!std::filesystem::exists(path)) throw InputError(s.source, 0, key, record_not_found(path));
  ReadOptions ro;
  if (g.format == RecordFormat::columns) ro.unit = *declared_unit(g);
  if (g.dt) ro.dt = *g.dt;
  Format f = Format::automatic;
  switch (g.format) {
    case RecordFormat::at2: f = Format::peer_at2; break;
    case RecordFormat::knet: f = Format::knet; break;
    case RecordFormat::jma_csv: f = Format::jma_csv; break;
    case RecordFormat::columns: f = Format::columns; break;
  }
  Record r = read_record(path, f, ro);
  check_record_pga(s, r, key);
  return r;
}

// Window and low-pass one component; the run's time 0 is the window's start. A window that holds
// fewer than two samples of the record names its key, the record and its span; so does a window.end
// past the record's end (unless pad_after_end) and a low-pass corner at or above the record's Nyquist
// frequency (it was skipped silently). Not scaled: scene_table_motion scales.
inline Record process_record(Record r, const SceneSpec& s) {
  const GroundMotionSpec& g = s.ground_motion;
  const std::string span = "record '" + r.name + "' (" + r.source + "), which spans [" + fmt(r.t0) + ", " +
                           fmt(r.t_end()) + "] s";
  if (g.lowpass_hz > 0 && !(g.lowpass_hz < 0.5 / r.dt))
    throw InputError(s.source, 0, "ground_motion.lowpass_hz",
                     fmt(g.lowpass_hz) + " Hz is not below the Nyquist frequency " + fmt(0.5 / r.dt) + " Hz of " +
                         "record '" + r.name + "' (" + r.source + ", dt = " + fmt(r.dt) +
                         " s): set a lower corner, or 0 for no filter");
  if (g.window_end && *g.window_end > r.t_end() + 1e-6 * r.dt && !g.pad_after_end &&
      g.window_start <= r.t_end() - r.dt)
    throw InputError(s.source, 0, "ground_motion.window.end",
                     fmt(*g.window_end) + " s is past the end of " + span +
                         "; end the window within the record, or set \"pad_after_end\": true to run on with the "
                         "table at rest after the record's end");
  if (g.lowpass_hz > 0) r = low_pass(r, g.lowpass_hz);
  const double t0 = std::max(g.window_start, r.t0);
  const double t1 = g.window_end ? std::min(*g.window_end, r.t_end()) : r.t_end();
  // The samples window() keeps (within 1e-6 dt of a bound counts as inside).
  const double first = std::ceil((t0 - r.t0) / r.dt - 1e-6), last = std::floor((t1 - r.t0) / r.dt + 1e-6);
  if (!(last - first >= 1)) {
    const bool late = !g.window_end || g.window_start > r.t_end() - r.dt;
    throw InputError(s.source, 0, late ? "ground_motion.window.start" : "ground_motion.window.end",
                     fmt(late ? g.window_start : *g.window_end) + " s leaves fewer than two samples of " + span);
  }
  if (t0 > 0 || t1 < r.t_end()) r = window(r, t0, t1, 0.0);
  r.t0 = 0;
  return r;
}

// The peak of a component the scale target is defined on: |a| (pga) or |v| of the trapezoid velocity
// from rest (pgv), over the record's samples.
inline double scale_measure(const Record& r, ScaleMeasure m) {
  if (m == ScaleMeasure::pga) return r.peak();
  double v = 0, peak = 0;
  for (std::size_t i = 1; i < r.acc.size(); ++i) {
    v += 0.5 * r.dt * (r.acc[i - 1] + r.acc[i]);
    peak = std::max(peak, std::abs(v));
  }
  return peak;
}

// The factor that brings the motion to the scale target, 1 without one: its horizontal components'
// largest peak (x, and y when given) for pga and pgv; the intensity of every component given (x, y,
// z) for jma. A record whose peak is zero, or that the intensity cannot be taken of, is an InputError.
inline double scale_factor(const SceneSpec& s, const Record& x, const Record* y, const Record* z) {
  const GroundMotionSpec& g = s.ground_motion;
  if (!g.scale_to) return 1.0;
  const ScaleMeasure m = g.scale_to->measure;
  const std::string key = "ground_motion.scale_to." + enum_name(scale_measure_names, m);
  if (m == ScaleMeasure::jma) {
    std::vector<std::reference_wrapper<const Record>> c{x};
    if (y) c.emplace_back(*y);
    if (z) c.emplace_back(*z);
    try {
      return jma_scale_factor(jma_intensity(c).intensity, g.scale_to->value);
    } catch (const InputError& e) {
      throw InputError(s.source, 0, key, std::string(e.what()) + " (after window and filter): it cannot be scaled to " +
                                             fmt(g.scale_to->value));
    }
  }
  double peak = scale_measure(x, m);
  if (y) peak = std::max(peak, scale_measure(*y, m));
  if (!(peak > 0) || !std::isfinite(peak))
    throw InputError(s.source, 0, key, "the record's horizontal " + enum_name(scale_measure_names, m) + " is " +
                                           fmt(peak) + " (after window and filter): it cannot be scaled to " +
                                           fmt(g.scale_to->value));
  const double k = g.scale_to->value / peak;
  if (!std::isfinite(k) || !(k > 0))
    throw InputError(s.source, 0, key, "scaling the record's horizontal " + enum_name(scale_measure_names, m) + " " +
                                           fmt(peak) + " to " + fmt(g.scale_to->value) + " needs a factor of " + fmt(k));
  return k;
}

}  // namespace detail

// The ground's acceleration for a scene (m/s^2, table axes): the table's without a building. A file
// record is read, checked against the plausible peak band (check_pga), windowed and low-passed, then
// scaled to ground_motion.scale_to (the factor in *scale_factor, 1 without a target) and by `level`.
inline TableMotion scene_ground_motion(const SceneSpec& s, double* scale_factor = nullptr) {
  const auto& g = s.ground_motion;
  const bool three_d = g.dimensions == MotionDimensions::three_d;
  if (scale_factor) *scale_factor = 1.0;
  if (g.source == MotionSource::points) {
    const auto component = [](const std::vector<std::pair<double, double>>& pts) {
      PiecewiseLinear p;
      for (const auto& [t, a] : pts) {
        p.t.push_back(t);
        p.a.push_back(a);
      }
      return p;
    };
    return TableMotion::from_points(component(g.points_x), component(g.points_y), component(g.points_z)).scaled(g.level);
  }
  if (g.source == MotionSource::synthetic) {
    TableMotion m = default_table_motion(g.seed, g.synthetic_duration);
    // Scale so the X component's peak is the requested PGA; Y and Z keep their ratios to X.
    const double k = g.pga / std::max(m.x.peak(), 1e-12);
    m = m.scaled(k * g.level);
    if (!three_d) m.has_y = m.has_z = false;
    return m;
  }
  std::array<Record, 3> c;
  if (g.format == RecordFormat::jma_csv) {
    c = read_jma_csv(s.resolve(g.file_x));
    for (int k = 0; k < (three_d ? 3 : 1); ++k) detail::check_record_pga(s, c[k], "ground_motion.files.x");
  } else {
    c[0] = detail::scene_record(s, g.file_x, "x");
    if (three_d) {
      c[1] = detail::scene_record(s, g.file_y, "y");
      c[2] = detail::scene_record(s, g.file_z, "z");
    }
  }
  for (int k = 0; k < (three_d ? 3 : 1); ++k) c[k] = detail::process_record(std::move(c[k]), s);
  const double k = detail::scale_factor(s, c[0], three_d ? &c[1] : nullptr, three_d ? &c[2] : nullptr);
  if (scale_factor) *scale_factor = k;
  const double factor = k * g.level;
  if (!three_d) return TableMotion::one_d(c[0].scaled(factor));
  return TableMotion::three_d(c[0].scaled(factor), c[1].scaled(factor), c[2].scaled(factor));
}

// The shake table's acceleration for a scene (m/s^2, table axes), as the scene asks for it: the ground's
// (scene_ground_motion, scaled as it says), or with ground_motion.building that of the building's storey.
inline TableMotion scene_table_motion(const SceneSpec& s, double* scale_factor = nullptr) {
  TableMotion ground = scene_ground_motion(s, scale_factor);
  if (!s.ground_motion.building) return ground;
  if (s.ground_motion.source == MotionSource::points)
    throw InputError(s.source, 0, "ground_motion.building", "not used with source \"points\"");
  return detail::building_floor_motion(s, ground);
}

// The time the scene's motion ends (s of run time): the shortest component's end (a file record after
// its window, the synthetic motion's duration); infinite for "points" (zero after the last point, as given).
inline double motion_end(const SceneSpec& s, const TableMotion& m) {
  if (s.ground_motion.source == MotionSource::points) return std::numeric_limits<double>::infinity();
  double e = m.x.t_end();
  if (m.has_y) e = std::min(e, m.y.t_end());
  if (m.has_z) e = std::min(e, m.z.t_end());
  return e;
}

}  // namespace furniture_fem
