#pragma once
// Internal: the standard normal's CDF in forms that stay finite far in the tails, its quantile, and
// the type-7 quantile of sorted data. The fragility likelihood needs ln Phi(t) and phi(t)/Phi(t) at |t| of 40 and
// more (a level many dispersions from the median, or a Newton step that overshoots), where Phi(t)
// itself underflows to 0 and ln 0 would turn a finite likelihood into -inf or NaN.
#ifndef FURNITURE_FEM_STUDY_INTERNAL
#error "furniture_fem/study/detail/normal_tail.hpp is internal: include <furniture_fem/study/statistics.hpp>"
#endif
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace furniture_fem::detail {

// Below this, erfc(-t/sqrt 2) nears the smallest normal double: use Phi's asymptotic series instead.
inline constexpr double normal_tail_switch = -35.0;

// phi(t), the standard normal density.
inline double normal_pdf(double t) { return std::exp(-0.5 * t * t) / std::sqrt(2.0 * std::numbers::pi); }

// Phi(t) by the C library's erfc, accurate in relative terms in the lower tail (1 - erf would cancel).
// Not Boost.Math's erfc: every target above contact compiles with CGAL's -frounding-math, and with
// it GCC 12 folds Boost.Math's long-double coefficient literals to garbage (boostorg/math#1133, a GCC
// bug): boost::math::erfc(1.0) returns NaN and the normal quantile NaN in such a translation unit.
inline double normal_cdf(double t) { return 0.5 * std::erfc(-t / std::numbers::sqrt2); }

// Phi^-1(p) for 0 < p < 1: Abramowitz and Stegun 26.2.23 (error < 4.5e-4) as the start, then Halley's
// iteration on Phi(z) = p through erfc (cubic convergence: three steps reach the rounding of erfc).
inline double normal_quantile(double p) {
  if (p > 0.5) return -normal_quantile(1.0 - p);  // 1 - p is exact for p >= 1/2 (Sterbenz)
  const double t = std::sqrt(-2.0 * std::log(p));
  double z = -(t - (2.515517 + t * (0.802853 + t * 0.010328)) / (1.0 + t * (1.432788 + t * (0.189269 + t * 0.001308))));
  for (int i = 0; i < 8; ++i) {
    const double f = (normal_cdf(z) - p) / normal_pdf(z);  // Newton's step
    const double step = f / (1.0 + 0.5 * z * f);           // Halley's correction (Phi'' = -z phi)
    z -= step;
    if (std::abs(step) <= 1e-15 * std::abs(z)) break;
  }
  return z;
}

// Phi(t) / (phi(t) / -t) for t << 0: Laplace's asymptotic series 1 - 1/t^2 + 3/t^4 - 15/t^6 + 105/t^8;
// at t <= -35 the next term (945/t^10) is below 1e-12.
inline double normal_tail_series(double t) {
  const double u = 1.0 / (t * t);
  return 1.0 - u * (1.0 - 3.0 * u * (1.0 - 5.0 * u * (1.0 - 7.0 * u)));
}

// ln Phi(t), finite for every finite t.
inline double log_normal_cdf(double t) {
  if (t < normal_tail_switch)
    return -0.5 * t * t - std::log(-t) - 0.5 * std::log(2.0 * std::numbers::pi) + std::log(normal_tail_series(t));
  if (t > 0.0) return std::log1p(-normal_cdf(-t));  // Phi(t) near 1: keep the small complement's digits
  return std::log(normal_cdf(t));
}

// phi(t) / Phi(t) (the inverse Mills ratio), finite for every finite t; it tends to -t as t -> -inf.
inline double normal_mills(double t) {
  if (t < normal_tail_switch) return -t / normal_tail_series(t);
  return normal_pdf(t) / normal_cdf(t);
}

// The q-quantile of sorted, non-empty data by Hyndman and Fan's type 7 (numpy's and R's default):
// linear interpolation between the order statistics at h = (n - 1) q.
inline double sorted_quantile(const std::vector<double>& sorted, double q) {
  const double h = static_cast<double>(sorted.size() - 1) * q;
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = lo + 1 < sorted.size() ? lo + 1 : lo;
  const double frac = h - static_cast<double>(lo);
  // Equal neighbours (or an infinite one) would give inf - inf: no interpolation needed there.
  if (frac == 0.0 || sorted[lo] == sorted[hi]) return sorted[lo];
  return sorted[lo] + frac * (sorted[hi] - sorted[lo]);
}

}  // namespace furniture_fem::detail
