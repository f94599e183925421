#pragma once
// furniture_fem/excitation/synthetic.hpp: Seeded synthetic motions (the toolkit's default input) and pulses.
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
#include "processing.hpp"
#include "spectrum.hpp"
#define FURNITURE_FEM_EXCITATION_INTERNAL
#include "detail/excitation_dsp.hpp"
#undef FURNITURE_FEM_EXCITATION_INTERNAL

namespace furniture_fem {

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
