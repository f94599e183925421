// The JMA instrumental seismic intensity against closed forms: a steady sinusoid's filtered amplitude
// is A G(f0), so its intensity follows from G alone; scaling adds 2 log10 k; bad records are named.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <furniture_fem/excitation/excitation.hpp>

namespace seismic_intensity_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double kPi = 3.14159265358979323846;

// A A sin(2 pi f0 t + phase) held for `steady` s between 10 s cosine ramps: the ramps keep the
// filter's overshoot at the ends below 0.03 % (measured; 3 s ramps left 0.3 %).
furniture_fem::Record tone(double f0, double phase, double steady, double amplitude = 3.0, double dt = 0.002) {
  constexpr double ramp = 10.0;
  furniture_fem::Record r;
  r.name = "tone";
  r.source = "test";
  r.dt = dt;
  for (std::size_t i = 0; double(i) * dt < steady + 2 * ramp; ++i) {
    const double t = double(i) * dt;
    const double e = t < ramp                  ? 0.5 - 0.5 * std::cos(kPi * t / ramp)
                     : t > ramp + steady ? 0.5 + 0.5 * std::cos(kPi * (t - ramp - steady) / ramp)
                                         : 1.0;
    r.acc.push_back(amplitude * e * std::sin(2 * kPi * f0 * t + phase));
  }
  return r;
}

double intensity_of(double a0) { return 2.0 * std::log10(100.0 * a0) + 0.94; }  // a0 in m/s^2

}  // namespace

TEST_CASE("JMA intensity: the filter's gain is the notification's three filters", "[excitation][jma]") {
  // At 1 Hz: period effect 1, high cut (1 + 0.694 0.01 + 0.241 1e-4 + ...)^(-1/2), low cut sqrt(1 - e^-8).
  const double high = 1.0 / std::sqrt(1 + 0.00694 + 0.241e-4 + 0.0557e-6 + 0.009664e-8 + 0.00134e-10 + 0.000155e-12);
  CHECK(furniture_fem::jma_filter_gain(1.0) == Approx(high * std::sqrt(1 - std::exp(-8.0))).epsilon(1e-14));
  CHECK(furniture_fem::jma_filter_gain(0.0) == 0.0);
  // Far below 0.5 Hz the low cut goes as (f/0.5)^1.5, so the gain as f: halving f halves it.
  CHECK(furniture_fem::jma_filter_gain(0.01) / furniture_fem::jma_filter_gain(0.02) == Approx(0.5).epsilon(1e-3));
}

TEST_CASE("JMA intensity: a steady tone and a circular motion, against their closed forms", "[excitation][jma]") {
  // One component A sin: |v| >= a for the fraction 1 - (2/pi) asin(a/B) of the time, B = A G(f0), so
  // 0.3 s of `steady` s gives a0 = B cos(0.15 pi / steady). Two components in quadrature (a circle):
  // |v| = B throughout, a0 = B. Measured to within 6e-5 (tone) and 2.7e-4 (circle, the ramps' overshoot)
  // of I over 0.3 to 8 Hz; the bound 5e-4 of I is 0.06 % of a0.
  const double steady = 40.0;
  for (double f0 : {0.3, 1.0, 2.0, 5.0, 8.0}) {
    CAPTURE(f0);
    const double B = 3.0 * furniture_fem::jma_filter_gain(f0);
    const auto x = tone(f0, 0.0, steady), y = tone(f0, kPi / 2, steady);
    CHECK(furniture_fem::jma_intensity({x}).intensity ==
          Approx(intensity_of(B * std::cos(0.15 * kPi / steady))).margin(5e-4));
    const auto circle = furniture_fem::jma_intensity({x, y});
    CHECK(circle.intensity == Approx(intensity_of(B)).margin(5e-4));
    CHECK(circle.a0 == Approx(B).epsilon(1e-3));
  }
}

TEST_CASE("JMA intensity: scaling a motion by k adds 2 log10 k, and the reported class", "[excitation][jma]") {
  const auto x = tone(1.5, 0.3, 20.0), y = tone(2.5, 1.0, 20.0, 2.0), z = tone(4.0, 0.0, 20.0, 1.0);
  const double I = furniture_fem::jma_intensity({x, y, z}).intensity;
  for (double k : {0.25, 0.7, 3.0}) {
    CAPTURE(k);
    const auto xk = x.scaled(k), yk = y.scaled(k), zk = z.scaled(k);
    CHECK(furniture_fem::jma_intensity({xk, yk, zk}).intensity ==
          Approx(I + 2 * std::log10(k)).margin(1e-12));
    CHECK(furniture_fem::jma_scale_factor(I, I + 2 * std::log10(k)) == Approx(k).epsilon(1e-12));
  }
  // JMA rounds at the third decimal and cuts to one: 6.449 is reported 6.4, 6.4951 is 6.5.
  furniture_fem::JmaIntensity j;
  const std::vector<std::pair<double, std::string>> classes{
      {0.4, "0"},       {2.49, "2"},       {4.4951, "5-lower"}, {4.99, "5-lower"}, {5.2, "5-upper"},
      {5.5, "6-lower"}, {6.449, "6-upper"}, {6.4951, "7"},      {7.3, "7"}};
  for (const auto& [value, name] : classes) {
    j.intensity = value;
    CAPTURE(value);
    CHECK(j.scale_class() == name);
  }
  j.intensity = 6.449;
  CHECK(j.reported() == Approx(6.4).margin(1e-12));
}

TEST_CASE("JMA intensity: records it cannot measure are named", "[excitation][jma]") {
  auto x = tone(1.0, 0.0, 5.0), y = tone(1.0, 0.0, 5.0);
  y.name = "ew";
  y.dt = 0.005;
  CHECK_THROWS_WITH(furniture_fem::jma_intensity({x, y}), Catch::Contains("'ew'") && Catch::Contains("dt = 0.005"));
  y = x;
  y.acc[7] = std::nan("");
  y.name = "ud";
  CHECK_THROWS_WITH(furniture_fem::jma_intensity({x, y}), Catch::Contains("'ud'") && Catch::Contains("sample 7"));
  auto quiet = x.scaled(0.0);
  CHECK_THROWS_WITH(furniture_fem::jma_intensity({quiet}), Catch::Contains("no motion"));
  quiet.acc.resize(100);  // 0.2 s
  CHECK_THROWS_WITH(furniture_fem::jma_intensity({quiet}), Catch::Contains("at least 0.3 s"));
}

}  // namespace seismic_intensity_tests
