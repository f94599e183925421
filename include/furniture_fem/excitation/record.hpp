#pragma once
// furniture_fem/excitation/record.hpp: Records: one component of acceleration (Record), a piecewise-linear function, the table motion.
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
#include "../core/model.hpp"  // standard_gravity

namespace furniture_fem {


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

}  // namespace furniture_fem
