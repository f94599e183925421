#pragma once
// furniture_fem/excitation/processing.hpp: Processing a record: resampling, baseline correction, zero-phase low-pass, windowing, integration.
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
#include "record_io.hpp"
#define FURNITURE_FEM_EXCITATION_INTERNAL
#include "detail/excitation_dsp.hpp"
#undef FURNITURE_FEM_EXCITATION_INTERNAL

namespace furniture_fem {

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

}  // namespace furniture_fem
