// Record processing (interpolation, resampling, baseline, low-pass, window, integration) and the
// table motion, each against a closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <furniture_fem/excitation/excitation.hpp>

namespace processing_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double kPi = 3.14159265358979323846;

template <class F>
furniture_fem::Record make_record(double dt, std::size_t n, F&& f, double t0 = 0) {
  furniture_fem::Record r;
  r.name = "test";
  r.dt = dt;
  r.t0 = t0;
  r.acc.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.acc[i] = f(t0 + dt * double(i));
  return r;
}

// Largest |a - b| over samples with time in [t_from, t_to].
double max_diff(const furniture_fem::Record& a, const furniture_fem::Record& b, double t_from, double t_to) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a.time(i) >= t_from && a.time(i) <= t_to) m = std::max(m, std::abs(a.acc[i] - b.acc[i]));
  return m;
}

double max_abs(const furniture_fem::Record& a, double t_from, double t_to) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a.time(i) >= t_from && a.time(i) <= t_to) m = std::max(m, std::abs(a.acc[i]));
  return m;
}

}  // namespace

TEST_CASE("value_at: linear interpolation a0 + (t - t0)/dt (a1 - a0), 0 outside [t0, t_end]", "[excitation][record]") {
  const furniture_fem::Record r{"r", "", 0.5, {1.0, 3.0, -1.0}, 2.0};
  CHECK(r.duration() == 1.0);
  CHECK(r.t_end() == 3.0);
  CHECK(r.value_at(2.0) == 1.0);
  CHECK(r.value_at(2.125) == Approx(1.5));
  CHECK(r.value_at(2.75) == Approx(1.0));
  CHECK(r.value_at(3.0) == -1.0);
  CHECK(r.value_at(1.999) == 0.0);
  CHECK(r.value_at(3.001) == 0.0);
  CHECK(r.value_at(std::nan("")) == 0.0);
  CHECK(r.peak() == 3.0);
  CHECK(r.peak_time() == 2.5);
  CHECK(r.scaled(0.5).acc[1] == 1.5);
  CHECK(furniture_fem::Record{}.value_at(0.0) == 0.0);
}

TEST_CASE("TableMotion: 1-D moves in X only, 3-D in all, scaled(level) multiplies every axis", "[excitation][record]") {
  const furniture_fem::Record x{"x", "", 0.1, {0.0, 1.0, 2.0}, 0.0};
  const furniture_fem::Record y{"y", "", 0.1, {0.0, -1.0, -2.0}, 0.0};
  const furniture_fem::Record z{"z", "", 0.2, {0.0, 4.0}, 0.0};
  const auto one = furniture_fem::TableMotion::one_d(x);
  CHECK_FALSE(one.is_3d());
  CHECK(one.at(0.15).isApprox(Eigen::Vector3d(1.5, 0, 0)));
  const auto three = furniture_fem::TableMotion::three_d(x, y, z);
  CHECK(three.is_3d());
  CHECK(three.at(0.15).isApprox(Eigen::Vector3d(1.5, -1.5, 3.0)));
  CHECK(three(0.15).isApprox(three.at(0.15)));
  CHECK(three.scaled(0.5).at(0.15).isApprox(Eigen::Vector3d(0.75, -0.75, 1.5)));
  CHECK(three.at(0.5).isZero());
  CHECK(three.t_end() == Approx(0.2));
}

TEST_CASE("resample: linear interpolation keeps a linear record a = 1 + 2t exactly", "[excitation][processing]") {
  const auto r = make_record(0.02, 501, [](double t) { return 1.0 + 2.0 * t; }, 0.3);
  const auto fine = furniture_fem::resample(r, 0.005);
  REQUIRE(fine.size() == 2001);
  CHECK(fine.t0 == r.t0);
  CHECK(fine.dt == 0.005);
  for (std::size_t i = 0; i < fine.size(); ++i) REQUIRE(fine.acc[i] == Approx(1.0 + 2.0 * fine.time(i)).epsilon(1e-12));
  const auto coarse = furniture_fem::resample(r, 0.03);
  CHECK(coarse.size() == 334);  // floor(10 / 0.03) + 1
  CHECK(coarse.acc.back() == Approx(1.0 + 2.0 * coarse.time(333)).epsilon(1e-12));
}

TEST_CASE("extreme time steps: resample refuses more than 1e9 samples, low_pass pads within the record",
          "[excitation][processing][errors]") {
  // Issue 13 (fuzzing): low_pass converted 3 / (f_cut dt), 3e300 for dt = 1e-300, to size_t (undefined
  // behaviour, UBSan); resample to 1e-12 s over 1 s asked for 1e12 samples.
  furniture_fem::Record r;
  r.name = "tiny";
  r.dt = 1e-300;
  r.acc = {1.0, 2.0, 3.0, 4.0};
  const furniture_fem::Record lp = furniture_fem::low_pass(r, 1.0);
  REQUIRE(lp.acc.size() == 4);
  // 1 Hz on a record of 3e-300 s: the padding is the whole record (odd reflection), the result finite.
  for (const double a : lp.acc) CHECK(std::isfinite(a));
  furniture_fem::Record second;
  second.name = "one second";
  second.dt = 0.01;
  second.acc.assign(101, 1.0);
  try {
    (void)furniture_fem::resample(second, 1e-12);
    FAIL("no InputError");
  } catch (const furniture_fem::InputError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("resample") && Catch::Contains("at most 1e9"));
  }
}

TEST_CASE("baseline_correct: a polynomial trend of the given order is removed exactly", "[excitation][processing]") {
  const auto linear = make_record(0.01, 1001, [](double t) { return 0.3 + 0.2 * t; });
  for (double a : furniture_fem::baseline_correct(linear, 1).acc) REQUIRE(std::abs(a) < 1e-12);
  const auto quad = make_record(0.01, 1001, [](double t) { return 1.0 - 0.5 * t + 0.05 * t * t; });
  for (double a : furniture_fem::baseline_correct(quad, 2).acc) REQUIRE(std::abs(a) < 1e-12);
  const auto offset = make_record(0.01, 11, [](double) { return -4.0; });
  for (double a : furniture_fem::baseline_correct(offset, 0).acc) REQUIRE(std::abs(a) < 1e-14);

  // On a signal plus a trend: the residual satisfies the normal equations sum r = sum r t = 0, and
  // the signal part orthogonal to (1, t) is left.
  const auto mixed = make_record(0.01, 1001, [](double t) { return std::sin(2 * kPi * 1.3 * t) + 0.3 + 0.2 * t; });
  const auto c = furniture_fem::baseline_correct(mixed, 1);
  double s0 = 0, s1 = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    s0 += c.acc[i];
    s1 += c.acc[i] * c.time(i);
  }
  CHECK(std::abs(s0) < 1e-10);
  CHECK(std::abs(s1) < 1e-10);
  const auto sine_only = furniture_fem::baseline_correct(make_record(0.01, 1001, [](double t) { return std::sin(2 * kPi * 1.3 * t); }), 1);
  CHECK(max_diff(c, sine_only, 0, 10) < 1e-12);

  // zero_final_velocity: the trapezoid velocity ends at 0.
  const auto z = furniture_fem::baseline_correct(mixed, 1, true);
  CHECK(std::abs(furniture_fem::integrate(z).vel.back()) < 1e-13);
  CHECK_THROWS_AS(furniture_fem::baseline_correct(mixed, 3), furniture_fem::InputError);
}

TEST_CASE("low_pass 10 Hz, zero phase: 2 Hz passes (|H|^2 = 1/(1 + (f/fc)^16) ~ 1), 30 Hz is cut, fc gives 1/2",
          "[excitation][processing]") {
  const double dt = 0.005;
  const auto s2 = make_record(dt, 2001, [](double t) { return std::sin(2 * kPi * 2.0 * t); });
  const auto f2 = furniture_fem::low_pass(s2, 10.0);
  // Amplitude within 1 % and no shift: the pointwise difference is below 1 % of the amplitude.
  CHECK(max_diff(f2, s2, 1.0, 9.0) < 0.01);
  CHECK(max_abs(f2, 1.0, 9.0) == Approx(1.0).epsilon(0.01));
  // The peak at t = 2.125 s (a crest of the 2 Hz sine) stays at the same sample.
  std::size_t k_in = 0, k_out = 0;
  for (std::size_t i = 400; i < 440; ++i) {
    if (s2.acc[i] > s2.acc[k_in]) k_in = i;
    if (f2.acc[i] > f2.acc[k_out]) k_out = i;
  }
  CHECK(k_in == 425);
  CHECK(k_out == k_in);
  // Even near the ends the padding keeps the error small.
  CHECK(max_diff(f2, s2, 0.0, 10.0) < 0.02);

  const auto s30 = make_record(dt, 2001, [](double t) { return std::sin(2 * kPi * 30.0 * t); });
  CHECK(max_abs(furniture_fem::low_pass(s30, 10.0), 1.0, 9.0) < 0.02);

  // At the cut-off the forward-backward Butterworth gain is |H(fc)|^2 = 1/2 (prewarped: exact).
  const auto s10 = make_record(dt, 2001, [](double t) { return std::cos(2 * kPi * 10.0 * t); });
  CHECK(max_abs(furniture_fem::low_pass(s10, 10.0), 2.0, 8.0) == Approx(0.5).epsilon(2e-3));
  // An odd order (a first-order section in the cascade): |H(fc)|^2 = 1/2 as well.
  CHECK(max_abs(furniture_fem::low_pass(s10, 10.0, 3), 2.0, 8.0) == Approx(0.5).epsilon(2e-3));
  // A constant passes unchanged (unit DC gain and steady-state start).
  const auto c = make_record(dt, 100, [](double) { return 3.0; });
  for (double a : furniture_fem::low_pass(c, 10.0).acc) REQUIRE(a == Approx(3.0).epsilon(1e-12));
  CHECK_THROWS_AS(furniture_fem::low_pass(s2, 100.0), furniture_fem::InputError);  // at Nyquist
}

TEST_CASE("window: kept samples in [t_start, t_end], cosine taper 0.5 (1 - cos(pi d / taper))", "[excitation][processing]") {
  const auto r = make_record(0.01, 1001, [](double) { return 1.0; });
  const auto w = furniture_fem::window(r, 2.0, 6.0, 0.5);
  REQUIRE(w.size() == 401);
  CHECK(w.t0 == Approx(2.0).epsilon(1e-12));
  CHECK(w.acc.front() == Approx(0.0).margin(1e-15));
  CHECK(w.acc.back() == Approx(0.0).margin(1e-15));
  CHECK(w.acc[25] == Approx(0.5).epsilon(1e-12));        // 0.25 s into the taper
  CHECK(w.acc[10] == Approx(0.5 * (1 - std::cos(kPi * 0.1 / 0.5))).epsilon(1e-12));
  CHECK(w.acc[200] == 1.0);
  CHECK(w.acc[400 - 25] == Approx(0.5).epsilon(1e-12));
  // No taper: a plain cut.
  const auto cut = furniture_fem::window(r, 0.005, 0.5);
  CHECK(cut.size() == 50);
  CHECK(cut.t0 == Approx(0.01));
  CHECK_THROWS_AS(furniture_fem::window(r, 20.0, 30.0), furniture_fem::InputError);
}

TEST_CASE("integrate (trapezoid): constant a gives v = a t and d = a t^2 / 2 exactly", "[excitation][processing]") {
  const double a = 2.5;
  const auto r = make_record(0.01, 1001, [&](double) { return a; });
  const auto k = furniture_fem::integrate(r);
  REQUIRE(k.vel.size() == 1001);
  for (std::size_t i = 0; i < r.size(); ++i) {
    const double t = r.time(i);
    REQUIRE(k.vel[i] == Approx(a * t).epsilon(1e-12).margin(1e-15));
    REQUIRE(k.disp[i] == Approx(0.5 * a * t * t).epsilon(1e-12).margin(1e-15));
  }
  // A linear acceleration c t: the trapezoid velocity c t^2 / 2 is exact too; v0, d0 are added.
  const auto lin = furniture_fem::integrate(make_record(0.01, 101, [](double t) { return 3.0 * t; }), 1.0, -2.0);
  CHECK(lin.vel.back() == Approx(1.0 + 1.5).epsilon(1e-12));
  CHECK(lin.disp.front() == -2.0);
}

}  // namespace processing_tests
