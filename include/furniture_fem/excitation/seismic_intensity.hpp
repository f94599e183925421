#pragma once
// furniture_fem/excitation/seismic_intensity.hpp: the JMA instrumental seismic intensity of a motion
// (Japan Meteorological Agency, notification No. 4 of 1996), the measure "6-upper" and "7" are read
// from, so a record can be scaled to "intensity 6-upper" as Japanese shake-table tests state their input.
// Part of furniture_fem/excitation/excitation.hpp; SI units throughout (the formula's gal inside).
//
// Each component is filtered in frequency, by the period effect sqrt(1/f), the high cut
// (1 + 0.694 y^2 + 0.241 y^4 + 0.0557 y^6 + 0.009664 y^8 + 0.00134 y^10 + 0.000155 y^12)^(-1/2), y = f/10,
// and the low cut sqrt(1 - exp(-(f/0.5)^3)), f in Hz; v(t) is the filtered components' vector sum;
// a0 is the largest a with v >= a for 0.3 s in all; I = 2 log10(a0 [gal]) + 0.94. Scaling a motion by k
// adds 2 log10(k) to I. docs/excitation/ground_motions.md, "JMA seismic intensity".
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "../core/errors.hpp"
#include "record.hpp"
#define FURNITURE_FEM_EXCITATION_INTERNAL
#include "detail/excitation_text.hpp"
#undef FURNITURE_FEM_EXCITATION_INTERNAL

namespace furniture_fem {

// The JMA filter's gain at f Hz (the three filters' product); 0 at f = 0.
inline double jma_filter_gain(double f) {
  if (!(f > 0)) return 0.0;
  const double y2 = (f / 10.0) * (f / 10.0);
  const double high_cut = 1 + y2 * (0.694 + y2 * (0.241 + y2 * (0.0557 + y2 * (0.009664 + y2 * (0.00134 + y2 * 0.000155)))));
  return std::sqrt(1.0 / f) / std::sqrt(high_cut) * std::sqrt(1.0 - std::exp(-std::pow(f / 0.5, 3)));
}

struct JmaIntensity {
  double intensity = 0;  // I, unrounded
  double a0 = 0;         // m/s^2: the filtered vector acceleration exceeded for 0.3 s in all
  // The value JMA reports: rounded at the third decimal, then cut to one (6.449 -> 6.4).
  [[nodiscard]] double reported() const { return std::floor(std::round(intensity * 100.0) / 10.0 + 1e-9) / 10.0; }
  // The scale's class of the reported value: "0" to "4", "5-lower", "5-upper", "6-lower", "6-upper", "7".
  [[nodiscard]] std::string scale_class() const {
    const double r = reported();
    if (r < 0.5) return "0";
    if (r < 4.5) return std::to_string(static_cast<int>(std::floor(r + 0.5)));
    if (r < 5.0) return "5-lower";
    if (r < 5.5) return "5-upper";
    if (r < 6.0) return "6-lower";
    if (r < 6.5) return "6-upper";
    return "7";
  }
};

namespace detail {

// One component filtered: zero-padded to a power of two at least twice its length, so that the
// filter's tail does not wrap round onto the record's start.
inline std::vector<double> jma_filtered(const Record& r, std::size_t n_fft) {
  std::vector<double> x(n_fft, 0.0);
  std::copy(r.acc.begin(), r.acc.end(), x.begin());
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, x);
  for (std::size_t k = 0; k < spectrum.size(); ++k) {
    const std::size_t m = std::min(k, n_fft - k);  // the frequency of bin k, folded
    spectrum[k] *= jma_filter_gain(double(m) / (double(n_fft) * r.dt));
  }
  fft.inv(x, spectrum);
  return x;
}

}  // namespace detail

// The JMA intensity of one to three components (x, y, z, m/s^2), sampled alike (the same dt; a shorter
// one is zero after its end). The three of a record for the official value; fewer give the intensity of
// the motion a run gets. Throws InputError naming the record for a mismatched dt, a non-finite sample,
// fewer samples than 0.3 s, or no motion.
inline JmaIntensity jma_intensity(const std::vector<std::reference_wrapper<const Record>>& components) {
  if (components.empty()) throw InputError("jma_intensity: no component given");
  const Record& first = components.front().get();
  std::size_t n = 0;
  const auto named = [](const Record& r) { return "jma_intensity: record '" + r.name + "' (" + r.source + ")"; };
  for (const Record& r : components) {
    if (!(r.dt > 0) || std::abs(r.dt - first.dt) > 1e-9 * first.dt)
      throw InputError(named(r) + " has dt = " + detail::gm::num(r.dt) + " s; every component must be sampled alike (" +
                       named(first) + " has dt = " + detail::gm::num(first.dt) + " s)");
    for (std::size_t i = 0; i < r.acc.size(); ++i)
      if (!std::isfinite(r.acc[i]))
        throw InputError(named(r) + ": sample " + std::to_string(i) + " is " + detail::gm::num(r.acc[i]) +
                         " (the intensity needs finite accelerations)");
    n = std::max(n, r.acc.size());
  }
  const auto above = static_cast<std::size_t>(std::ceil(0.3 / first.dt - 1e-9));  // samples in 0.3 s
  if (n < above)
    throw InputError(named(first) + " has " + std::to_string(n) + " samples of " + detail::gm::num(first.dt) +
                     " s: the intensity needs at least 0.3 s of motion");
  std::size_t n_fft = 1;
  while (n_fft < 2 * n) n_fft *= 2;
  std::vector<double> v2(n_fft, 0.0);
  for (const Record& r : components) {
    const std::vector<double> f = detail::jma_filtered(r, n_fft);
    for (std::size_t i = 0; i < n_fft; ++i) v2[i] += f[i] * f[i];
  }
  // The largest a that v reaches for `above` samples: the above-th largest v.
  std::nth_element(v2.begin(), v2.begin() + std::ptrdiff_t(above - 1), v2.end(), std::greater<>());
  JmaIntensity out;
  out.a0 = std::sqrt(v2[above - 1]);
  if (!(out.a0 > 0))
    throw InputError(named(first) + " has no motion: its intensity is not defined");
  out.intensity = 2.0 * std::log10(100.0 * out.a0) + 0.94;
  return out;
}

// The factor that brings a motion of intensity `from` to intensity `to`: I grows by 2 log10 of it.
inline double jma_scale_factor(double from, double to) { return std::pow(10.0, 0.5 * (to - from)); }

}  // namespace furniture_fem
