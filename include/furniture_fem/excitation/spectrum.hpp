#pragma once
// furniture_fem/excitation/spectrum.hpp: Response spectra of a record by the exact piecewise-linear recurrence.
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

}  // namespace furniture_fem
