// The statistics users cite (study/statistics.hpp), each against a source outside this code:
// published tables (Newcombe 1998 for the Wilson interval; Fagerland, Lydersen and Laake 2017 for the
// paired difference), an independent Python implementation (tests/study/statistics_reference.py,
// standard library only, written from the papers' formulas), and for the fragility fit the known
// parameters of synthetic data drawn from a lognormal CDF.
#include <catch2/catch.hpp>

#include <furniture_fem/study/statistics.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace furniture_fem;
using Catch::Matchers::Contains;

namespace statistics_tests {  // this file's own names (its group compiles files in batches)

namespace {

double phi_cdf(double t) { return 0.5 * std::erfc(-t / std::sqrt(2.0)); }

// 8 intensity levels (g), as a study's IDA stripes would be.
const std::vector<double> stripes = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};

// Synthetic outcomes: each realisation at each level fails with P = Phi(ln(im/theta)/beta), by
// RandomStream draws (key 2^40 keeps these streams apart from a bootstrap's {resample, level} keys).
std::vector<FragilityLevel> synthetic(double theta, double beta, long trials, std::uint64_t seed) {
  std::vector<FragilityLevel> levels;
  for (std::size_t l = 0; l < stripes.size(); ++l) {
    RandomStream stream(seed, {std::uint64_t{1} << 40, l});
    const double p = phi_cdf(std::log(stripes[l] / theta) / beta);
    long failures = 0;
    for (long k = 0; k < trials; ++k) failures += stream.bernoulli(p) ? 1 : 0;
    levels.push_back({stripes[l], trials, failures});
  }
  return levels;
}

}  // namespace

TEST_CASE("normal quantile: Python's NormalDist.inv_cdf", "[statistics]") {
  // The z of every interval. Python's inv_cdf (Wichura's AS241, 1e-16 relative) is another algorithm
  // than ours (a rational start polished by Halley's iteration on erfc); agreement to 1e-14 relative
  // is a few ulps. This test's translation unit has CGAL's -frounding-math, under which Boost.Math's
  // quantile returned NaN (statistics.md): the check also guards that.
  struct Row { double confidence, z; };
  for (const Row& r : {Row{0.5, 0.6744897501960817}, Row{0.9, 1.6448536269514715}, Row{0.95, 1.9599639845400536},
                       Row{0.99, 2.5758293035489}, Row{0.999999, 4.891638475671084}}) {
    INFO("confidence " << r.confidence);
    CHECK(detail::two_sided_z(r.confidence) == Approx(r.z).epsilon(1e-14));
  }
  CHECK(detail::normal_quantile(1e-10) == Approx(-6.361340902404056).epsilon(1e-14));
  CHECK(detail::normal_quantile(1e-300) == Approx(-37.0470962993612).epsilon(1e-14));
  CHECK(detail::normal_quantile(0.3) == Approx(-0.5244005127080407).epsilon(1e-14));
}

TEST_CASE("Wilson interval: Newcombe (1998) Table II, method 3, and the Python reference", "[statistics]") {
  // Newcombe, "Two-sided confidence intervals for the single proportion: comparison of seven methods",
  // Stat Med 17:857-872, Table II, method 3 (score, no continuity correction), printed to 4 decimals:
  // a correct value is within half a unit of the 4th decimal, 5e-5.
  struct Row { long x, n; double lo, hi; };
  const Row table[] = {{81, 263, 0.2553, 0.3662}, {15, 148, 0.0624, 0.1605}, {0, 20, 0.0, 0.1611}, {1, 29, 0.0061, 0.1718}};
  for (const Row& r : table) {
    const ProportionEstimate e = wilson_interval(r.x, r.n);
    INFO(r.x << "/" << r.n);
    CHECK(e.successes == r.x);
    CHECK(e.trials == r.n);
    CHECK(e.p == Approx(double(r.x) / r.n).epsilon(1e-15));
    CHECK(std::abs(e.lo - r.lo) <= 5e-5);
    CHECK(std::abs(e.hi - r.hi) <= 5e-5);
  }
  // The same rows (and a 99 % interval, for the confidence argument) to 10 decimals from the Python
  // reference (statistics.NormalDist's quantile, not Boost's); both sides are double-precision
  // evaluations of one closed form, so 1e-9 only allows for the printed rounding (5e-11) and ulps.
  struct Exact { long x, n; double confidence, lo, hi; };
  const Exact python[] = {{81, 263, 0.95, 0.2552885199, 0.3662095770}, {15, 148, 0.95, 0.0623863995, 0.1604872417},
                          {0, 20, 0.95, 0.0, 0.1611251581}, {1, 29, 0.95, 0.0061132143, 0.1717552188},
                          {7, 40, 0.99, 0.0706442350, 0.3718333537}};
  for (const Exact& r : python) {
    const ProportionEstimate e = wilson_interval(r.x, r.n, r.confidence);
    INFO(r.x << "/" << r.n << " at " << r.confidence);
    CHECK(std::abs(e.lo - r.lo) <= 1e-9);
    CHECK(std::abs(e.hi - r.hi) <= 1e-9);
  }
  // All successes mirrors none: [1 - 0.1611..., 1] exactly at the top.
  const ProportionEstimate all = wilson_interval(20, 20);
  CHECK(all.hi == 1.0);
  CHECK(std::abs(all.lo - (1.0 - 0.1611251581)) <= 1e-9);
}

TEST_CASE("Wilson interval: bad inputs name their values", "[statistics]") {
  CHECK_THROWS_AS(wilson_interval(0, 0), std::invalid_argument);
  CHECK_THROWS_WITH(wilson_interval(0, 0), Contains("trials = 0"));
  CHECK_THROWS_WITH(wilson_interval(1, -3), Contains("trials = -3"));
  CHECK_THROWS_WITH(wilson_interval(-1, 10), Contains("successes = -1"));
  CHECK_THROWS_WITH(wilson_interval(11, 10), Contains("successes = 11, trials = 10"));
  CHECK_THROWS_WITH(wilson_interval(1, 10, 1.0), Contains("confidence = 1"));
  CHECK_THROWS_WITH(wilson_interval(1, 10, 0.0), Contains("confidence = 0"));
  CHECK_THROWS_WITH(wilson_interval(1, 10, std::nan("")), Contains("confidence = nan"));
}

TEST_CASE("describe: type-7 quantiles as numpy computes them", "[statistics]") {
  // Expected values: Python's statistics.quantiles(method="inclusive") (Hyndman-Fan type 7, numpy's
  // default) in statistics_reference.py; by hand for [3, 1, 2]: h = 2 * 0.16 = 0.32 -> 1 + 0.32 * (2 - 1).
  // Interpolation is one multiply-add on exact inputs, so 1e-12 relative allows only rounding.
  struct Case { std::vector<double> v; double min, p16, median, p84, max, mean; };
  const Case cases[] = {{{3.0, 1.0, 2.0}, 1, 1.32, 2, 2.68, 3, 2},
                        {{0.5, 2.5, -1.0, 4.0, 10.0, 7.5, 3.25}, -1, 0.44, 3.25, 7.6, 10, 3.82142857143},
                        {{42.0}, 42, 42, 42, 42, 42, 42},
                        {{1.0, 1.0, 2.0, 9.0}, 1, 1, 1.5, 5.64, 9, 3.25}};
  for (const Case& c : cases) {
    const Distribution d = describe(c.v);
    CHECK(d.count == static_cast<long>(c.v.size()));
    CHECK(d.min == Approx(c.min).epsilon(1e-12));
    CHECK(d.p16 == Approx(c.p16).epsilon(1e-12));
    CHECK(d.median == Approx(c.median).epsilon(1e-12));
    CHECK(d.p84 == Approx(c.p84).epsilon(1e-12));
    CHECK(d.max == Approx(c.max).epsilon(1e-12));
    CHECK(d.mean == Approx(c.mean).epsilon(1e-11));  // the reference printed 12 significant digits
  }
  // Empty: count 0, every statistic NaN (documented), not a made-up 0.
  const Distribution empty = describe({});
  CHECK(empty.count == 0);
  CHECK(std::isnan(empty.min));
  CHECK(std::isnan(empty.median));
  CHECK(std::isnan(empty.mean));
  // A NaN cannot be ordered: an error naming its index.
  CHECK_THROWS_AS(describe({1.0, 2.0, std::nan(""), 4.0}), std::invalid_argument);
  CHECK_THROWS_WITH(describe({1.0, 2.0, std::nan(""), 4.0}), Contains("index = 2"));
}

TEST_CASE("paired difference: Newcombe's method 10 against a published example and the Python reference", "[statistics]") {
  // Published: Fagerland, Lydersen and Laake (2017), Statistical Analysis of Contingency Tables,
  // chapter 8, Cavo et al. (2012)'s complete response before/after consolidation, table
  // [[59, 6], [16, 80]]: Newcombe square-and-add estimate -0.0621, 95 % CI -0.1186 to -0.0046 (printed
  // to 4 decimals, also asserted by the R package contingencytables' tests): tolerance 5e-5.
  const PairedDifference cavo = paired_difference(59, 6, 16, 80);
  CHECK(cavo.n == 161);
  CHECK(cavo.p_a == Approx(65.0 / 161).epsilon(1e-15));
  CHECK(cavo.p_b == Approx(75.0 / 161).epsilon(1e-15));
  CHECK(std::abs(cavo.difference - -0.0621) <= 5e-5);
  CHECK(std::abs(cavo.lo - -0.1186) <= 5e-5);
  CHECK(std::abs(cavo.hi - -0.0046) <= 5e-5);
  CHECK(cavo.distinguishable);  // the interval lies below 0
  // Python reference (newcombe10 in statistics_reference.py, printed to 10 decimals): tables with the
  // phi adjustment active (eh - fg > n/2), a zero marginal cell (phi from an empty margin -> 0), a
  // negative phi, and one whose interval ends a hair above 0.
  struct Row { long e, f, g, h; double d, lo, hi; bool distinguishable; };
  const Row rows[] = {{59, 6, 16, 80, -0.0621118012, -0.1186211956, -0.0046251139, true},
                      {36, 12, 2, 0, 0.2, 0.0569295840, 0.3404276030, true},
                      {3, 9, 1, 27, 0.2, 0.0454139020, 0.3518264416, true},
                      {0, 0, 4, 16, -0.2, -0.4160174323, 0.0005091271, false},
                      {1, 7, 2, 40, 0.1, -0.0274302606, 0.2310208101, false}};
  for (const Row& r : rows) {
    const PairedDifference p = paired_difference(r.e, r.f, r.g, r.h);
    INFO(r.e << " " << r.f << " " << r.g << " " << r.h);
    CHECK(std::abs(p.difference - r.d) <= 1e-9);
    CHECK(std::abs(p.lo - r.lo) <= 1e-9);
    CHECK(std::abs(p.hi - r.hi) <= 1e-9);
    CHECK(p.distinguishable == r.distinguishable);
  }
  CHECK_THROWS_WITH(paired_difference(1, -2, 3, 4), Contains("only_a = -2"));
  CHECK_THROWS_WITH(paired_difference(0, 0, 0, 0), Contains("every count is 0"));
  CHECK_THROWS_WITH(paired_difference(1, 2, 3, 4, 1.5), Contains("confidence = 1.5"));
}

TEST_CASE("fragility fit: exact-fraction data return the generating theta and beta", "[statistics]") {
  // failures = round(10^6 Phi(ln(im/theta)/beta)): rounding moves each fraction by at most 5e-7, which
  // moves the estimates by O(1e-6) relative; 1e-4 leaves margin and still catches any real bias.
  for (auto [theta, beta] : {std::pair{0.4, 0.5}, std::pair{0.25, 0.3}, std::pair{1.3, 0.8}}) {
    std::vector<FragilityLevel> levels;
    for (double im : stripes) {
      const long n = 1000000;
      levels.push_back({im, n, std::lround(n * phi_cdf(std::log(im / theta) / beta))});
    }
    const LognormalFragility fit = fit_lognormal_fragility(levels);
    INFO("theta " << theta << " beta " << beta << ": " << fit.message);
    REQUIRE(fit.identifiable);
    CHECK(fit.converged);
    CHECK(fit.message.empty());
    CHECK(fit.theta == Approx(theta).epsilon(1e-4));
    CHECK(fit.beta == Approx(beta).epsilon(1e-4));
    CHECK(fragility_probability(fit, fit.theta) == Approx(0.5).epsilon(1e-12));
    CHECK(fragility_probability(fit, 0.3) == Approx(phi_cdf(std::log(0.3 / theta) / beta)).epsilon(1e-3));
  }
}

TEST_CASE("fragility fit: a small data set against an independent Nelder-Mead fit", "[statistics]") {
  // statistics_reference.py maximises the same binomial likelihood by Nelder-Mead over
  // (ln theta, ln beta) with Python's NormalDist: theta 0.4163356804, beta 0.5054701710,
  // log-likelihood -9.6002885905 (binomial coefficients included). The simplex stops at ~1e-10 in
  // the parameters and the maximum is flat there, so 1e-6 relative on the parameters, 1e-8 on ll.
  const std::vector<FragilityLevel> levels = {{0.1, 20, 0},  {0.2, 20, 2},  {0.3, 20, 5}, {0.4, 20, 9},
                                              {0.5, 20, 13}, {0.6, 20, 14}, {0.8, 20, 19}};
  const LognormalFragility fit = fit_lognormal_fragility(levels);
  REQUIRE(fit.identifiable);
  CHECK(fit.converged);
  CHECK(fit.theta == Approx(0.4163356804).epsilon(1e-6));
  CHECK(fit.beta == Approx(0.5054701710).epsilon(1e-6));
  CHECK(fit.log_likelihood == Approx(-9.6002885905).epsilon(1e-8));
  // Splitting a level into two entries at the same im pools to the same data: the same fit.
  std::vector<FragilityLevel> split = levels;
  split[3] = {0.4, 12, 5};
  split.push_back({0.4, 8, 4});
  const LognormalFragility same = fit_lognormal_fragility(split);
  CHECK(same.theta == Approx(fit.theta).epsilon(1e-12));
  CHECK(same.beta == Approx(fit.beta).epsilon(1e-12));
}

TEST_CASE("fragility fit: degenerate data are flagged with the reason, never NaN silently", "[statistics]") {
  auto expect_flagged = [](const std::vector<FragilityLevel>& levels, const std::string& why) {
    const LognormalFragility fit = fit_lognormal_fragility(levels);
    INFO(fit.message);
    CHECK_FALSE(fit.identifiable);
    CHECK_THAT(fit.message, Contains(why));
    CHECK(std::isnan(fit.theta));
    CHECK(std::isnan(fit.beta));
    CHECK_THROWS_WITH(fragility_probability(fit, 0.5), Contains(why));
  };
  expect_flagged({{0.2, 10, 0}, {0.4, 10, 0}, {0.8, 10, 0}}, "no realisation failed at any level: the median lies above the highest level (im = 0.8)");
  expect_flagged({{0.2, 10, 10}, {0.4, 10, 10}}, "every realisation failed at every level: the median lies below the lowest level (im = 0.2)");
  expect_flagged({{0.5, 10, 3}, {0.5, 20, 9}}, "a single intensity level (im = 0.5)");
  expect_flagged({{0.2, 10, 0}, {0.3, 10, 0}, {0.4, 10, 10}, {0.5, 10, 10}},
                 "perfectly separated (no failure below im = 0.4, every realisation failed above im = 0.3)");
  // One mixed level between pure ones: still no finite maximum (beta -> 0 with theta's fraction there).
  expect_flagged({{0.2, 10, 0}, {0.3, 10, 4}, {0.4, 10, 10}}, "perfectly separated");
  // Failure fractions falling with im: the best probit slope is negative.
  expect_flagged({{0.2, 10, 8}, {0.3, 10, 5}, {0.4, 10, 2}}, "do not rise with im");
  // Separated the wrong way round (all fail low, none high): the slope runs off to -infinity.
  expect_flagged({{0.2, 10, 10}, {0.4, 10, 0}}, "do not rise with im");
  // One failure at an inner level and none elsewhere (configuration 3's desk tilted past 10 deg at
  // `full`, 1 of 120 runs): the likelihood is flattest at slope 0, where the median is infinite.
  // Newton stopped at slope 0.0023 (beta 427), a median of e^1018, and called it identifiable.
  expect_flagged({{0.25, 20, 0}, {0.5, 20, 0}, {0.75, 20, 1}, {1.0, 20, 0}, {1.25, 20, 0}, {1.5, 20, 0}},
                 "the median lies beyond any level");
  // The same with a seventh level (0.625, the study of 2026-11-29): Newton stopped at slope 0.036
  // (beta 28) with a finite median of 3e29, and called it identifiable. The likelihood ratio against
  // one fraction at every level is 0 (an independent Nelder-Mead fit, statistics_reference-style: the
  // maximum is the flat model's, -5.7833); so is that of one failure at the highest level only (3.63).
  expect_flagged({{0.25, 20, 0}, {0.5, 20, 0}, {0.75, 20, 1}, {1.0, 20, 0}, {1.25, 20, 0}, {1.5, 20, 0}, {0.625, 20, 0}},
                 "below chi-square(1)'s 95 % point");
  // Fractions that do rise, weakly (0, 0, 1, 2, 3, 4 of 20 from 0.25 to 1.5): likelihood ratio 10.43
  // by the same independent fit, well above 3.84: a fit, theta 2.59 and beta 0.70 there.
  const LognormalFragility weak =
      fit_lognormal_fragility({{0.25, 20, 0}, {0.5, 20, 0}, {0.75, 20, 1}, {1.0, 20, 2}, {1.25, 20, 3}, {1.5, 20, 4}});
  INFO(weak.message);
  REQUIRE(weak.identifiable);
  CHECK(weak.theta == Approx(std::exp(1.3623 / 1.4335)).epsilon(2e-3));
  CHECK(weak.beta == Approx(1 / 1.4335).epsilon(2e-3));
  // Its resamples are fitted without the test: data whose rise is not significant (1 and 3 of 10,
  // likelihood ratio 1.30) get no fit, but most of their resamples do, and an interval.
  const FragilityInterval weak_boot = bootstrap_fragility({{0.2, 10, 1}, {0.4, 10, 3}}, 200, 5);
  CHECK_FALSE(weak_boot.fit.identifiable);
  CHECK_THAT(weak_boot.fit.message, Contains("below chi-square(1)'s 95 % point"));
  CHECK(weak_boot.not_identifiable < 100);
  CHECK(std::isfinite(weak_boot.theta_lo));
  CHECK(std::isfinite(weak_boot.theta_hi));
  // The bootstrap of such data forms no interval and says so.
  const FragilityInterval none = bootstrap_fragility({{0.2, 10, 0}, {0.4, 10, 10}}, 50, 7);
  CHECK(none.not_identifiable == 50);
  CHECK(std::isnan(none.theta_lo));
  CHECK_THAT(none.message, Contains("no resample had an identifiable fit"));
  CHECK_THAT(none.message, Contains("perfectly separated"));
}

TEST_CASE("fragility fit: bad inputs name their values", "[statistics]") {
  CHECK_THROWS_WITH(fit_lognormal_fragility({}), Contains("no intensity levels"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{0.1, 10, 1}, {0.0, 10, 2}}), Contains("level 1: im must be positive and finite (im = 0)"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{-0.3, 10, 1}}), Contains("im = -0.3"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{std::nan(""), 10, 1}}), Contains("im = nan"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{HUGE_VAL, 10, 1}}), Contains("im = inf"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{0.1, 0, 0}}), Contains("trials = 0"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{0.1, 10, 11}}), Contains("failures = 11, trials = 10"));
  CHECK_THROWS_WITH(fit_lognormal_fragility({{0.1, 10, -1}}), Contains("failures = -1"));
  const std::vector<FragilityLevel> ok = {{0.2, 20, 2}, {0.4, 20, 12}};
  CHECK_THROWS_WITH(bootstrap_fragility(ok, 0, 1), Contains("resamples = 0"));
  CHECK_THROWS_WITH(bootstrap_fragility(ok, 10, 1, 1.2), Contains("confidence = 1.2"));
  CHECK_THROWS_WITH(fragility_probability(fit_lognormal_fragility(ok), -1.0), Contains("im = -1"));
}

TEST_CASE("fragility bootstrap: intervals hold the truth, shrink with trials, and are reproducible", "[statistics]") {
  // 2 (theta, beta) pairs x 3 sample sizes x 2 parameters = 12 truths, each inside its 95 % interval
  // with probability ~0.95, so all 12 together only with ~0.54: at least 10 of 12 are required
  // (P(X <= 9 | 12, 0.95) = 0.02). The first run had one miss: beta of the steep pair at 30 trials,
  // whose estimate (0.222 for 0.3) is 1.8 Fisher standard errors low, a draw, not a bias (the
  // coverage test below measures that). The data seed was not changed to hide it.
  int covered = 0;
  for (auto [theta, beta] : {std::pair{0.4, 0.5}, std::pair{0.25, 0.3}}) {
    double previous_theta_width = HUGE_VAL, previous_beta_width = HUGE_VAL;
    for (long trials : {10L, 30L, 100L}) {
      const std::vector<FragilityLevel> data = synthetic(theta, beta, trials, 20261126);
      const FragilityInterval b = bootstrap_fragility(data, 1000, 99);
      INFO("theta " << theta << " beta " << beta << " trials " << trials << ": fit " << b.fit.theta << ", "
                    << b.fit.beta << "; theta [" << b.theta_lo << ", " << b.theta_hi << "], beta [" << b.beta_lo
                    << ", " << b.beta_hi << "], " << b.not_identifiable << " not identifiable");
      REQUIRE(b.fit.identifiable);
      CHECK(b.resamples == 1000);
      // Separated resamples: none with 100 trials a level (a level at p ~ 0.25 resampled to 0 of 100
      // has probability 0.75^100 ~ 3e-13); many with 10 trials on the steep pair, where only three
      // levels have both outcomes: the exclusion path is exercised and counted.
      if (trials == 100) CHECK(b.not_identifiable == 0);
      if (trials == 10 && beta == 0.3) CHECK(b.not_identifiable > 0);
      covered += (b.theta_lo <= theta && theta <= b.theta_hi) + (b.beta_lo <= beta && beta <= b.beta_hi);
      CHECK(b.theta_lo <= b.fit.theta);
      CHECK(b.fit.theta <= b.theta_hi);
      // More trials per level, narrower intervals (theta's in ratio, its natural scale).
      const double theta_width = std::log(b.theta_hi / b.theta_lo), beta_width = b.beta_hi - b.beta_lo;
      CHECK(theta_width < previous_theta_width);
      CHECK(beta_width < previous_beta_width);
      previous_theta_width = theta_width, previous_beta_width = beta_width;
    }
  }
  CHECK(covered >= 10);
  // Bit-reproducible from the seed (RandomStream); another seed gives other resamples.
  const std::vector<FragilityLevel> data = synthetic(0.4, 0.5, 30, 5);
  const FragilityInterval one = bootstrap_fragility(data, 200, 11), two = bootstrap_fragility(data, 200, 11);
  const FragilityInterval other = bootstrap_fragility(data, 200, 12);
  CHECK(one.theta_lo == two.theta_lo);
  CHECK(one.theta_hi == two.theta_hi);
  CHECK(one.beta_lo == two.beta_lo);
  CHECK(one.beta_hi == two.beta_hi);
  CHECK(one.theta_lo != other.theta_lo);
}

TEST_CASE("fragility bootstrap: 95 % intervals cover the truth in most of 40 independent data sets", "[statistics]") {
  // 40 data sets (30 trials at each of 8 levels, theta 0.4, beta 0.5), a 95 % percentile interval from
  // 400 resamples each. If the intervals covered at the nominal 95 %, the number covering would be
  // Binomial(40, 0.95); percentile intervals of a small-sample MLE undercover a little (measured over
  // 1000 such data sets: theta 0.931, beta 0.914; 0.953 and 0.937 at 100 trials), so take 0.92 as
  // the rate to protect: P(X <= 31 | 40, 0.92) = 0.0037 (0.0001 at 0.95), so requiring at least
  // 32 of 40 (80 %) fails a correct method with probability < 0.4 %, while a method covering 70 % would
  // pass with P(X >= 32 | 40, 0.70) = 0.11 and one covering 50 % with 1e-4. (The seeds are fixed, so
  // the outcome is deterministic; the argument says the bound was not tuned to these seeds.)
  int theta_covered = 0, beta_covered = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const FragilityInterval b = bootstrap_fragility(synthetic(0.4, 0.5, 30, seed), 400, 1000 + seed);
    theta_covered += b.theta_lo <= 0.4 && 0.4 <= b.theta_hi;
    beta_covered += b.beta_lo <= 0.5 && 0.5 <= b.beta_hi;
  }
  INFO("theta covered " << theta_covered << "/40, beta covered " << beta_covered << "/40");
  CHECK(theta_covered >= 32);
  CHECK(beta_covered >= 32);
}

}  // namespace statistics_tests
