#pragma once
// furniture_fem/study/statistics.hpp: the statistics a study's users cite (docs/study/statistics.md).
//
//   wilson_interval(successes, trials, confidence)        a proportion with its Wilson score interval
//   describe(values)                                       count, min, p16, median, p84, max, mean
//   fit_lognormal_fragility(levels)                        maximum-likelihood lognormal fragility (theta, beta)
//   bootstrap_fragility(levels, resamples, seed, conf.)   percentile intervals of theta and beta
//   fragility_probability(fit, im)                         P(failure | im) of a fitted fragility
//   paired_difference(both, only_a, only_b, neither, c.)   p_a - p_b on the same realisations (Newcombe 10)
//
// Only the standard library: a user's analysis script can include this without the scene module. The
// normal distribution is written out on the C library's erfc (detail/normal_tail.hpp says why not
// Boost.Math's). Every random draw comes from RandomStream, so a bootstrap is bit-reproducible from its seed.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "random.hpp"

#define FURNITURE_FEM_STUDY_INTERNAL
#include "detail/normal_tail.hpp"
#undef FURNITURE_FEM_STUDY_INTERNAL

namespace furniture_fem {

namespace detail {

// "what (name = value)" for std::invalid_argument messages; a double in its shortest form that reads
// back to the same value (-0.3, not -0.29999999999999999).
inline std::string value_text(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}
template <class T>
std::string bad_value(const std::string& what, const std::string& name, T value) {
  std::string text;
  if constexpr (std::is_floating_point_v<T>) text = value_text(value);
  else text = std::to_string(value);
  return what + " (" + name + " = " + text + ")";
}

inline void check_confidence(const char* function, double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0))
    throw std::invalid_argument(bad_value(std::string(function) + ": confidence must lie in (0, 1)", "confidence", confidence));
}

// The two-sided standard normal quantile z_{1 - (1 - confidence)/2}.
inline double two_sided_z(double confidence) { return normal_quantile(0.5 + 0.5 * confidence); }

}  // namespace detail

// ---------------------------------------------------------------- a proportion

struct ProportionEstimate {
  long successes = 0;
  long trials = 0;
  double p = 0;   // successes / trials
  double lo = 0;  // Wilson score interval
  double hi = 0;
};

// The Wilson (1927) score interval without continuity correction (Newcombe 1998, method 3): unlike
// the Wald interval it stays inside [0, 1] and keeps near-nominal coverage at 0 or all successes,
// which a study's failure counts often are.
inline ProportionEstimate wilson_interval(long successes, long trials, double confidence = 0.95) {
  if (trials <= 0) throw std::invalid_argument(detail::bad_value("wilson_interval: trials must be positive", "trials", trials));
  if (successes < 0 || successes > trials) {
    std::ostringstream s;
    s << "wilson_interval: successes must lie in [0, trials] (successes = " << successes << ", trials = " << trials << ")";
    throw std::invalid_argument(s.str());
  }
  detail::check_confidence("wilson_interval", confidence);
  const double z = detail::two_sided_z(confidence), n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n, z2n = z * z / n;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / n + 0.25 * z2n / n);
  // At 0 or all successes the limit is exactly 0 or 1; rounding could put it a hair outside.
  const double lo = successes == 0 ? 0.0 : std::max(0.0, centre - half);
  const double hi = successes == trials ? 1.0 : std::min(1.0, centre + half);
  return {successes, trials, p, lo, hi};
}

// ---------------------------------------------------------------- a sample of outcomes

struct Distribution {
  long count = 0;
  double min = 0, p16 = 0, median = 0, p84 = 0, max = 0, mean = 0;
};

// Order statistics and mean of `values`. Quantiles are Hyndman and Fan's (1996) type 7, linear
// interpolation between order statistics at h = (n - 1) q, which is numpy's and R's default, so a
// user re-computing them gets the same digits. p16 and p84 bracket the median by one standard deviation
// of a normal sample. Empty input gives count 0 and NaN everywhere else (nothing to describe, and
// a caller printing it shows "nan" rather than a made-up 0). A NaN value is an error: it cannot be
// ordered, and dropping it silently would hide a failed realisation.
inline Distribution describe(std::vector<double> values) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (values.empty()) return {0, nan, nan, nan, nan, nan, nan};
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::isnan(values[i])) throw std::invalid_argument(detail::bad_value("describe: value is NaN", "index", i));
  double sum = 0;
  for (double v : values) sum += v;
  std::sort(values.begin(), values.end());
  return {static_cast<long>(values.size()),
          values.front(),
          detail::sorted_quantile(values, 0.16),
          detail::sorted_quantile(values, 0.5),
          detail::sorted_quantile(values, 0.84),
          values.back(),
          sum / static_cast<double>(values.size())};
}

// ---------------------------------------------------------------- lognormal fragility

// The outcomes at one intensity level: `failures` of `trials` realisations failed at intensity `im`.
struct FragilityLevel {
  double im = 0;
  long trials = 0;
  long failures = 0;
};

// P(failure | im) = Phi(ln(im / theta) / beta).
struct LognormalFragility {
  double theta = std::numeric_limits<double>::quiet_NaN();  // median, in the unit of im
  double beta = std::numeric_limits<double>::quiet_NaN();   // dispersion (standard deviation of ln capacity)
  double log_likelihood = std::numeric_limits<double>::quiet_NaN();  // binomial, coefficients included
  bool identifiable = false;  // false: theta, beta and log_likelihood are NaN and `message` says why
  bool converged = false;     // Newton's method met its tolerance
  int iterations = 0;
  std::string message;
};

namespace detail {

inline void check_levels(const std::vector<FragilityLevel>& levels) {
  if (levels.empty()) throw std::invalid_argument("fit_lognormal_fragility: no intensity levels");
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const FragilityLevel& l = levels[i];
    const std::string at = "fit_lognormal_fragility: level " + std::to_string(i);
    if (!(l.im > 0.0 && std::isfinite(l.im))) throw std::invalid_argument(bad_value(at + ": im must be positive and finite", "im", l.im));
    if (l.trials <= 0) throw std::invalid_argument(bad_value(at + ": trials must be positive", "trials", l.trials));
    if (l.failures < 0 || l.failures > l.trials) {
      std::ostringstream s;
      s << at << ": failures must lie in [0, trials] (failures = " << l.failures << ", trials = " << l.trials << ")";
      throw std::invalid_argument(s.str());
    }
  }
}

// Levels at equal im pooled and sorted by im, so degeneracy is judged per intensity, not per entry.
inline std::vector<FragilityLevel> pooled_levels(std::vector<FragilityLevel> levels) {
  std::sort(levels.begin(), levels.end(), [](const auto& a, const auto& b) { return a.im < b.im; });
  std::vector<FragilityLevel> pooled;
  for (const FragilityLevel& l : levels) {
    if (!pooled.empty() && pooled.back().im == l.im) {
      pooled.back().trials += l.trials;
      pooled.back().failures += l.failures;
    } else {
      pooled.push_back(l);
    }
  }
  return pooled;
}


// Why the maximum-likelihood estimate does not exist (an empty string if it may). Without at least one
// intensity that sits between failures and survivals, the likelihood keeps growing as beta -> 0 or as
// theta runs off past the data (Albert and Anderson 1984's separation, for a probit with one covariate).
inline std::string why_not_identifiable(const std::vector<FragilityLevel>& pooled) {
  long failures = 0, trials = 0;
  for (const auto& l : pooled) failures += l.failures, trials += l.trials;
  if (failures == 0)
    return "no realisation failed at any level: the median lies above the highest level (im = " + value_text(pooled.back().im) + ")";
  if (failures == trials)
    return "every realisation failed at every level: the median lies below the lowest level (im = " + value_text(pooled.front().im) + ")";
  if (pooled.size() == 1)
    return "a single intensity level (im = " + value_text(pooled.front().im) + "): one fraction cannot fix both the median and the dispersion";
  // Separation: every level below some im has no failure, every level above it fails throughout.
  std::size_t first_failure = pooled.size(), last_survival = 0;
  for (std::size_t g = 0; g < pooled.size(); ++g) {
    if (pooled[g].failures > 0 && first_failure == pooled.size()) first_failure = g;
    if (pooled[g].failures < pooled[g].trials) last_survival = g;
  }
  if (last_survival <= first_failure)
    return "the levels are perfectly separated (no failure below im = " + value_text(pooled[first_failure].im) +
           ", every realisation failed above im = " + value_text(pooled[last_survival].im) +
           "): the dispersion's estimate goes to 0 and the median is only bracketed";
  return "";
}

// The probit form of the model: P(failure) = Phi(a + b x), x = ln im, a = -ln(theta) / beta, b = 1 / beta.
// Its binomial log-likelihood is concave in (a, b) (Phi and 1 - Phi are log-concave), so Newton's method
// with a backtracking line search finds the unique maximum from any start; the maximum-likelihood
// estimate is the same point in (ln theta, ln beta), the likelihood being invariant to the parametrisation.
struct ProbitTerms {
  double ll = 0;                // log-likelihood without the binomial coefficients
  double ga = 0, gb = 0;        // gradient
  double haa = 0, hab = 0, hbb = 0;  // Hessian (negative definite when two intensities carry weight)
};

inline ProbitTerms probit_terms(const std::vector<FragilityLevel>& pooled, double a, double b) {
  ProbitTerms t;
  for (const auto& l : pooled) {
    const double x = std::log(l.im), eta = a + b * x;
    const double f = static_cast<double>(l.failures), s = static_cast<double>(l.trials - l.failures);
    // d/d eta of f ln Phi(eta) + s ln Phi(-eta), through the inverse Mills ratios (finite in the tails).
    const double m1 = normal_mills(eta), m0 = normal_mills(-eta);
    t.ll += (f > 0 ? f * log_normal_cdf(eta) : 0.0) + (s > 0 ? s * log_normal_cdf(-eta) : 0.0);
    const double g = f * m1 - s * m0;
    const double h = -f * m1 * (eta + m1) - s * m0 * (m0 - eta);
    t.ga += g, t.gb += g * x;
    t.haa += h, t.hab += h * x, t.hbb += h * x * x;
  }
  return t;
}

// The log-likelihood (without the binomial coefficients) of one failure fraction at every level, the
// pooled one: the model a fragility curve must beat.
inline double flat_log_likelihood(const std::vector<FragilityLevel>& pooled) {
  double f = 0, n = 0;
  for (const auto& l : pooled) f += static_cast<double>(l.failures), n += static_cast<double>(l.trials);
  const double p = f / n;
  return (f > 0 ? f * std::log(p) : 0.0) + (n - f > 0 ? (n - f) * std::log1p(-p) : 0.0);
}
inline constexpr double chi2_1_95 = 3.841458820694124;  // the 95 % point of chi-square with 1 degree of freedom

// ln of the binomial coefficients, so log_likelihood is the data's probability, comparable across fits.
inline double log_binomial_coefficients(const std::vector<FragilityLevel>& pooled) {
  double c = 0;
  for (const auto& l : pooled)
    c += std::lgamma(l.trials + 1.0) - std::lgamma(l.failures + 1.0) - std::lgamma(l.trials - l.failures + 1.0);
  return c;
}

// Starting point: weighted least squares of the empirical probits Phi^-1((f + 1/2) / (n + 1)) on ln im
// (the 1/2 keeps a level with 0 or all failures finite); any start converges, a good one saves steps.
inline void probit_start(const std::vector<FragilityLevel>& pooled, double& a, double& b) {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& l : pooled) {
    const double w = static_cast<double>(l.trials), x = std::log(l.im);
    const double y = normal_quantile((l.failures + 0.5) / (l.trials + 1.0));
    sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
  }
  const double mx = sx / sw, my = sy / sw, vxx = sxx / sw - mx * mx;
  b = vxx > 0 ? (sxy / sw - mx * my) / vxx : 0.0;
  if (!(b > 0)) b = 1.0 / std::max(std::sqrt(std::max(vxx, 0.0)), 1e-3);  // a rising start if the probits do not rise
  a = my - b * mx;
}

}  // namespace detail

// Maximum-likelihood lognormal fragility (Baker 2015; FEMA P-58's lognormal convention): the levels'
// failure counts are independent binomials with P(failure | im) = Phi(ln(im / theta) / beta).
// Data whose likelihood has no finite maximum (no failure, only failures, one intensity, separated
// levels, or failure fractions that fall as im grows) return identifiable = false with a message; so
// do data whose rise is not significant (require_rise, below). The bootstrap fits its resamples
// without that test: a resample with a weak rise belongs to the spread its interval must show
// (excluding them narrowed tutorial step-8's median interval from [12.95, 57.73] to [12.94, 33.84]).
inline LognormalFragility fit_lognormal_fragility(const std::vector<FragilityLevel>& levels, bool require_rise = true) {
  detail::check_levels(levels);
  const std::vector<FragilityLevel> pooled = detail::pooled_levels(levels);
  LognormalFragility fit;
  fit.message = detail::why_not_identifiable(pooled);
  if (!fit.message.empty()) return fit;

  double a = 0, b = 0;
  detail::probit_start(pooled, a, b);
  detail::ProbitTerms t = detail::probit_terms(pooled, a, b);
  constexpr int max_iterations = 200;
  for (fit.iterations = 0; fit.iterations < max_iterations; ++fit.iterations) {
    // Newton direction d = -H^-1 g (2x2, by Cramer's rule); H is negative definite here.
    const double det = t.haa * t.hbb - t.hab * t.hab;
    if (!(det > 0) || !(t.haa < 0)) break;
    const double da = -(t.hbb * t.ga - t.hab * t.gb) / det, db = -(t.haa * t.gb - t.hab * t.ga) / det;
    const double decrement = t.ga * da + t.gb * db;  // g . d = g^T (-H)^-1 g >= 0
    // Half the Newton decrement is the predicted gain in ll: below rounding of ll, the maximum is reached.
    if (decrement < 1e-12 * (1.0 + std::abs(t.ll))) {
      fit.converged = true;
      break;
    }
    double step = 1.0;
    detail::ProbitTerms next;
    bool improved = false;
    for (int halvings = 0; halvings < 60; ++halvings, step *= 0.5) {  // Armijo backtracking
      next = detail::probit_terms(pooled, a + step * da, b + step * db);
      if (std::isfinite(next.ll) && next.ll >= t.ll + 1e-4 * step * decrement) {
        improved = true;
        break;
      }
    }
    if (!improved) {  // no step gains: ll's rounding hides the last digits of the maximum
      fit.converged = decrement < 1e-8 * (1.0 + std::abs(t.ll));
      break;
    }
    a += step * da, b += step * db, t = next;
  }
  if (!fit.converged) {
    fit.message = "Newton's method did not converge in " + std::to_string(fit.iterations) + " iterations";
    return fit;
  }
  if (!(b > 0)) {
    fit.message = "the failure fractions do not rise with im: the best probit slope is not positive, no lognormal fragility fits";
    return fit;
  }
  // A slope the data do not support: failures scattered over the levels without rising put the
  // maximum at or near slope 0, a flat curve at the overall failure fraction whose median runs off
  // beyond any level (one failure in 140 runs gave 3e29 times the record, beta 28). The test: the
  // likelihood ratio against one fraction at every level (slope 0) below chi-square(1)'s 95 % point.
  if (const double theta = std::exp(-a / b), D = 2 * (t.ll - detail::flat_log_likelihood(pooled));
      !std::isfinite(theta) || !std::isfinite(1.0 / b) || (require_rise && !(D >= detail::chi2_1_95))) {
    fit.message = "the failure fractions barely rise with im (probit slope " + detail::value_text(b) +
                  ", likelihood ratio against one fraction at every level " + detail::value_text(D) +
                  ", below chi-square(1)'s 95 % point 3.84): the median lies beyond any level, no lognormal fragility fits";
    return fit;
  }
  fit.identifiable = true;
  fit.beta = 1.0 / b;
  fit.theta = std::exp(-a / b);
  fit.log_likelihood = t.ll + detail::log_binomial_coefficients(pooled);
  return fit;
}

// P(failure | im) of an identifiable fit; im = 0 gives 0.
inline double fragility_probability(const LognormalFragility& fit, double im) {
  if (!fit.identifiable) throw std::invalid_argument("fragility_probability: the fit is not identifiable (" + fit.message + ")");
  if (!(im >= 0.0) || std::isinf(im)) throw std::invalid_argument(detail::bad_value("fragility_probability: im must be finite and >= 0", "im", im));
  if (im == 0.0) return 0.0;
  return detail::normal_cdf(std::log(im / fit.theta) / fit.beta);
}

struct FragilityInterval {
  LognormalFragility fit;  // the fit to the data themselves
  double confidence = 0.95;
  double theta_lo = std::numeric_limits<double>::quiet_NaN(), theta_hi = std::numeric_limits<double>::quiet_NaN();
  double beta_lo = std::numeric_limits<double>::quiet_NaN(), beta_hi = std::numeric_limits<double>::quiet_NaN();
  int resamples = 0;
  int not_identifiable = 0;  // resamples whose fit was not identifiable: excluded from the intervals
  std::string message;       // set when no interval could be formed
};

// Nonparametric bootstrap of the fit: in each resample every level's outcomes are resampled with
// replacement, i.e. its failures are `trials` Bernoulli draws at the observed fraction from
// RandomStream(seed, {resample, level}); the intervals are the type-7 percentiles (1 -+ confidence) / 2
// of the identifiable resamples' theta and beta. Resamples without a finite estimate (separated data,
// frequent with few trials per level) are excluded and counted: many of them mean the intervals are
// conditional on identifiability and too narrow.
inline FragilityInterval bootstrap_fragility(const std::vector<FragilityLevel>& levels, int resamples, std::uint64_t seed,
                                             double confidence = 0.95) {
  detail::check_confidence("bootstrap_fragility", confidence);
  if (resamples < 1) throw std::invalid_argument(detail::bad_value("bootstrap_fragility: resamples must be positive", "resamples", resamples));
  FragilityInterval out;
  out.fit = fit_lognormal_fragility(levels);
  out.confidence = confidence;
  out.resamples = resamples;
  std::vector<double> thetas, betas;
  std::vector<FragilityLevel> resample = levels;
  for (int r = 0; r < resamples; ++r) {
    for (std::size_t l = 0; l < levels.size(); ++l) {
      RandomStream stream(seed, {static_cast<std::uint64_t>(r), static_cast<std::uint64_t>(l)});
      const double p = static_cast<double>(levels[l].failures) / static_cast<double>(levels[l].trials);
      long failures = 0;
      for (long k = 0; k < levels[l].trials; ++k) failures += stream.bernoulli(p) ? 1 : 0;
      resample[l].failures = failures;
    }
    const LognormalFragility fit = fit_lognormal_fragility(resample, false);
    if (fit.identifiable) {
      thetas.push_back(fit.theta);
      betas.push_back(fit.beta);
    } else {
      ++out.not_identifiable;
    }
  }
  if (thetas.empty()) {
    out.message = "no resample had an identifiable fit" + (out.fit.identifiable ? std::string() : " (the data: " + out.fit.message + ")");
    return out;
  }
  std::sort(thetas.begin(), thetas.end());
  std::sort(betas.begin(), betas.end());
  const double lo = 0.5 * (1.0 - confidence), hi = 0.5 * (1.0 + confidence);
  out.theta_lo = detail::sorted_quantile(thetas, lo), out.theta_hi = detail::sorted_quantile(thetas, hi);
  out.beta_lo = detail::sorted_quantile(betas, lo), out.beta_hi = detail::sorted_quantile(betas, hi);
  return out;
}

// ---------------------------------------------------------------- two laws on the same realisations

struct PairedDifference {
  long n = 0;
  double p_a = 0, p_b = 0;
  double difference = 0;  // p_a - p_b
  double lo = 0, hi = 0;  // Newcombe's method 10
  bool distinguishable = false;  // the interval excludes 0
};

// The difference of two outcome rates measured on the same realisations (law A and law B each run on
// every realisation): `both` failed under both laws, `only_a` under A alone, and so on. The two rates
// are correlated, so the independent-samples interval is wrong; Newcombe's (1998) method 10 combines
// the Wilson intervals of the two marginals with the phi correlation of the 2x2 table, and keeps
// near-nominal coverage at small counts where the Wald interval fails.
inline PairedDifference paired_difference(long both, long only_a, long only_b, long neither, double confidence = 0.95) {
  if (both < 0 || only_a < 0 || only_b < 0 || neither < 0) {
    std::ostringstream s;
    s << "paired_difference: counts must be >= 0 (both = " << both << ", only_a = " << only_a << ", only_b = " << only_b
      << ", neither = " << neither << ")";
    throw std::invalid_argument(s.str());
  }
  const long n = both + only_a + only_b + neither;
  if (n == 0) throw std::invalid_argument("paired_difference: no realisations (every count is 0)");
  detail::check_confidence("paired_difference", confidence);
  const ProportionEstimate a = wilson_interval(both + only_a, n, confidence);
  const ProportionEstimate b = wilson_interval(both + only_b, n, confidence);
  // phi of the 2x2 table (in doubles: the product of four margins overflows a long), with Newcombe's
  // adjustment of a positive numerator by n/2 (a continuity-type correction; phi = 0 if it goes negative).
  const double margins = static_cast<double>(both + only_a) * static_cast<double>(only_b + neither) *
                         static_cast<double>(both + only_b) * static_cast<double>(only_a + neither);
  const double cross = static_cast<double>(both) * static_cast<double>(neither) - static_cast<double>(only_a) * static_cast<double>(only_b);
  const double numerator = cross > 0.5 * n ? cross - 0.5 * n : (cross < 0 ? cross : 0.0);
  const double phi = margins > 0 ? numerator / std::sqrt(margins) : 0.0;
  const double dl_a = a.p - a.lo, du_a = a.hi - a.p, dl_b = b.p - b.lo, du_b = b.hi - b.p;
  PairedDifference out;
  out.n = n;
  out.p_a = a.p, out.p_b = b.p;
  out.difference = a.p - b.p;
  out.lo = out.difference - std::sqrt(std::max(0.0, dl_a * dl_a - 2.0 * phi * dl_a * du_b + du_b * du_b));
  out.hi = out.difference + std::sqrt(std::max(0.0, du_a * du_a - 2.0 * phi * du_a * dl_b + dl_b * dl_b));
  out.distinguishable = out.lo > 0 || out.hi < 0;
  return out;
}

}  // namespace furniture_fem
