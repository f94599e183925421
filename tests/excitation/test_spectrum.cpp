// Elastic response spectra by the exact piecewise-linear recurrence, against closed-form SDOF
// responses.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <furniture_fem/excitation/excitation.hpp>

namespace spectrum_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double kPi = 3.14159265358979323846;

template <class F>
furniture_fem::Record make_record(double dt, std::size_t n, F&& f) {
  furniture_fem::Record r;
  r.name = "test";
  r.dt = dt;
  r.acc.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.acc[i] = f(dt * double(i));
  return r;
}

}  // namespace

TEST_CASE("spectrum: PSV = omega Sd and PSA = omega^2 Sd (to rounding), omega = 2 pi / T", "[excitation][spectrum]") {
  const auto rec = furniture_fem::synthetic_motion();
  const auto periods = furniture_fem::log_periods(0.02, 5.0, 40);
  const auto s = furniture_fem::response_spectrum(rec, periods);
  REQUIRE(s.sd.size() == 40);
  CHECK(s.zeta == 0.05);
  for (std::size_t i = 0; i < periods.size(); ++i) {
    const double w = 2.0 * kPi / periods[i];
    CHECK(s.periods[i] == periods[i]);
    CHECK(s.psv[i] == Approx(w * s.sd[i]).epsilon(1e-15));
    CHECK(s.psa[i] == Approx(w * w * s.sd[i]).epsilon(1e-15));
    CHECK(s.sd[i] > 0);
  }
  // A rigid oscillator (50 Hz) follows a ground motion without content near 50 Hz: Sa -> PGA.
  const auto smooth = furniture_fem::low_pass(rec, 5.0);
  const auto rigid = furniture_fem::response_spectrum(smooth, {0.02});
  CHECK(rigid.sa[0] == Approx(smooth.peak()).epsilon(0.01));
  CHECK(rigid.psa[0] == Approx(smooth.peak()).epsilon(0.01));
}

TEST_CASE("spectrum: undamped SDOF under a step a0 from rest: Sd = 2 a0 / omega^2, Sa = 2 a0", "[excitation][spectrum]") {
  const double a0 = 2.0;
  const auto step = make_record(0.01, 1001, [&](double) { return a0; });
  // T = 0.1, 1, 2 s at dt = 0.01 use the closed-form recurrence, T = 5 s at dt = 0.001 (w h = 0.0013)
  // the augmented exponential. The peaks (t = T/2) fall on samples, so both must be exact.
  for (double T : {1.0, 0.1, 2.0}) {
    const double w = 2 * kPi / T;
    const auto s = furniture_fem::response_spectrum(step, {T}, 0.0);
    CHECK(s.sd[0] == Approx(2 * a0 / (w * w)).epsilon(1e-6));
    CHECK(s.sa[0] == Approx(2 * a0).epsilon(1e-6));
    CHECK(s.sv[0] == Approx(a0 / w).epsilon(1e-6));  // u' = -(a0/w) sin(w t)
  }
  const auto fine = make_record(0.001, 10001, [&](double) { return a0; });
  const double w = 2 * kPi / 5.0;
  CHECK(furniture_fem::response_spectrum(fine, {5.0}, 0.0).sd[0] == Approx(2 * a0 / (w * w)).epsilon(1e-6));
}

TEST_CASE("spectrum: damped step overshoot Sd = a0/omega^2 (1 + exp(-zeta pi / sqrt(1 - zeta^2)))", "[excitation][spectrum]") {
  const double a0 = 1.5;
  for (double zeta : {0.02, 0.05, 0.2}) {
    for (double T : {0.5, 1.0}) {
      // The peak is at t = pi / omega_d: put it on a sample, 50 steps in (w h ~ 0.06, closed form)
      // and 2000 steps in (w h ~ 0.0016, augmented exponential).
      const double w = 2 * kPi / T, t_peak = kPi / (w * std::sqrt(1 - zeta * zeta));
      for (int steps : {50, 2000}) {
        const auto step = make_record(t_peak / steps, 4 * static_cast<std::size_t>(steps), [&](double) { return a0; });
        const auto s = furniture_fem::response_spectrum(step, {T}, zeta);
        INFO("zeta " << zeta << " T " << T << " steps to the peak " << steps);
        CHECK(s.sd[0] == Approx(a0 / (w * w) * (1 + std::exp(-zeta * kPi / std::sqrt(1 - zeta * zeta)))).epsilon(1e-6));
      }
    }
  }
}

TEST_CASE("spectrum: harmonic resonance, steady amplitude Sd = a0 / (2 zeta omega^2)", "[excitation][spectrum]") {
  const double T = 0.5, zeta = 0.05, a0 = 1.0, w = 2 * kPi / T;
  // 80 cycles: the start-up transient exp(-zeta w t) has decayed to 1e-11.
  const auto sine = make_record(T / 200, 16001, [&](double t) { return a0 * std::sin(w * t); });
  const auto s = furniture_fem::response_spectrum(sine, {T}, zeta);
  CHECK(s.sd[0] == Approx(a0 / (2 * zeta * w * w)).epsilon(1e-3));
  // At resonance the absolute acceleration amplitude is a0 sqrt(1 + 4 zeta^2) / (2 zeta).
  CHECK(s.sa[0] == Approx(a0 * std::sqrt(1 + 4 * zeta * zeta) / (2 * zeta)).epsilon(1e-3));
}

TEST_CASE("spectrum: resampling a sine input finer (same piecewise-linear input) changes Sd by < 0.5 %",
          "[excitation][spectrum]") {
  const auto coarse = make_record(0.02, 501, [](double t) { return 3.0 * std::sin(2 * kPi * 1.3 * t) * std::exp(-0.1 * t); });
  const auto periods = furniture_fem::log_periods(0.05, 4.0, 30);
  const auto a = furniture_fem::response_spectrum(coarse, periods);
  for (double dt : {0.01, 0.005, 0.001}) {
    const auto b = furniture_fem::response_spectrum(furniture_fem::resample(coarse, dt), periods);
    for (std::size_t i = 0; i < periods.size(); ++i) {
      INFO("dt " << dt << " T " << periods[i]);
      CHECK(b.sd[i] == Approx(a.sd[i]).epsilon(0.005));
    }
  }
}

TEST_CASE("SDOF step: closed-form Nigam-Jennings coefficients = augmented exponential at w h = 0.019", "[excitation][spectrum]") {
  // Just below the switch both forms are accurate, so they must agree.
  for (double zeta : {0.0, 0.05, 0.5}) {
    const double w = 7.0, h = 0.019 / w;
    const furniture_fem::detail::gm::SdofStep a(w, zeta, h, true), b(w, zeta, h);
    const double c[8] = {a.a11, a.a12, a.a21, a.a22, a.b11, a.b12, a.b21, a.b22};
    const double d[8] = {b.a11, b.a12, b.a21, b.a22, b.b11, b.b12, b.b21, b.b22};
    for (int k = 0; k < 8; ++k) CHECK(c[k] == Approx(d[k]).epsilon(1e-9));
  }
}

TEST_CASE("log_periods: geometric from t_min to t_max, both included", "[excitation][spectrum]") {
  const auto p = furniture_fem::log_periods(0.02, 5.0, 11);
  REQUIRE(p.size() == 11);
  CHECK(p.front() == 0.02);
  CHECK(p.back() == 5.0);
  for (std::size_t i = 1; i < p.size(); ++i) CHECK(p[i] / p[i - 1] == Approx(std::pow(250.0, 0.1)).epsilon(1e-12));
  CHECK_THROWS_AS(furniture_fem::log_periods(0.0, 1.0, 5), furniture_fem::InputError);
}

TEST_CASE("spectrum: a period too short or too long for the record's dt is refused, naming it", "[excitation][spectrum][input]") {
  // Substeps per sample dt / (T / 100) and free-vibration steps T / h became integers unchecked: 1e-300
  // s gave one substep, silently (undefined behaviour), 1e300 s ran for ever (issue 13).
  const auto rec = make_record(0.01, 100, [](double t) { return std::sin(10 * t); });
  using Catch::Matchers::Contains;
  REQUIRE_THROWS_WITH(furniture_fem::response_spectrum(rec, {1e-300}),
                      Contains("period 1e-300 s is too short") && Contains("dt 0.01 s"));
  REQUIRE_THROWS_WITH(furniture_fem::response_spectrum(rec, {1e300}), Contains("period 1e+300 s is too long"));
  CHECK_NOTHROW(furniture_fem::response_spectrum(rec, {1e-3, 1e3}));
}

}  // namespace spectrum_tests
