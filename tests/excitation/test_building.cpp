// A storey's floor motion in a linear shear building (excitation/building.hpp), against closed forms
// and an independent integration:
//  1. one storey is an SDOF oscillator: under a harmonic ground acceleration the floor's absolute
//     acceleration has the transfer function (1 + 2 i zeta r) / (1 - r^2 + 2 i zeta r); amplitude and
//     phase within 0.1 % (and 1e-3 rad) for r = 0.5, 1, 2 and zeta 0.02, 0.05;
//  2. a uniform N-storey building's circular frequencies against
//     w_j = 2 sqrt(k / m) sin((2j - 1) pi / (2 (2N + 1))), N = 1 to 60, every mode;
//  3. a non-uniform 6-storey building with Rayleigh damping under a multi-frequency record against a
//     direct integration of M u'' + C u' + K u = -M 1 a_g in floor coordinates (RK4 at a fiftieth of
//     the record's step, C = a0 M + a1 K formed from M and K, no modes);
//  4. bad buildings and floors are refused with the key, the index and the value.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <vector>

#include <furniture_fem/excitation/building.hpp>

namespace building_tests {  // this file's own names (its group compiles files in batches)

namespace {

using furniture_fem::Record;
using furniture_fem::ShearBuilding;
constexpr double kPi = 3.14159265358979323846;

template <class F>
Record sampled(double dt, double duration, F&& f) {
  Record r;
  r.name = "test";
  r.dt = dt;
  const auto n = static_cast<std::size_t>(std::llround(duration / dt)) + 1;
  r.acc.resize(n);
  for (std::size_t i = 0; i < n; ++i) r.acc[i] = f(dt * double(i));
  return r;
}

// Least-squares A sin(W t) + B cos(W t) over the samples from t_from on: amplitude and phase of
// amplitude * sin(W t + phase).
std::pair<double, double> harmonic_fit(const Record& r, double W, double t_from) {
  double ss = 0, sc = 0, cc = 0, ys = 0, yc = 0;
  for (std::size_t i = 0; i < r.acc.size(); ++i) {
    const double t = r.time(i);
    if (t < t_from) continue;
    const double s = std::sin(W * t), c = std::cos(W * t);
    ss += s * s, sc += s * c, cc += c * c, ys += r.acc[i] * s, yc += r.acc[i] * c;
  }
  const double det = ss * cc - sc * sc, A = (ys * cc - yc * sc) / det, B = (yc * ss - ys * sc) / det;
  return {std::hypot(A, B), std::atan2(B, A)};
}

}  // namespace

TEST_CASE("building: one storey is an SDOF oscillator, its floor's transfer function exact", "[excitation][building]") {
  const double T1 = 1.0, w = 2 * kPi / T1;
  for (const double zeta : {0.02, 0.05})
    for (const double r : {0.5, 1.0, 2.0}) {
      const double W = r * w;
      // The transient decays as exp(-zeta w t): below 1e-5 of it after 11.5 / (zeta w) s.
      const double settle = 11.5 / (zeta * w), duration = settle + 10 * 2 * kPi / W;
      const Record ground = sampled(5e-4, duration, [&](double t) { return std::sin(W * t); });
      const Record floor = furniture_fem::storey_motion(ShearBuilding::uniform(1, T1, zeta), 1, ground);
      const auto [amplitude, phase] = harmonic_fit(floor, W, settle);
      const std::complex<double> H = std::complex<double>(1, 2 * zeta * r) / std::complex<double>(1 - r * r, 2 * zeta * r);
      INFO("zeta " << zeta << " r " << r << ": amplitude " << amplitude << " against " << std::abs(H) << ", phase "
                   << phase << " against " << std::arg(H));
      CHECK(amplitude == Approx(std::abs(H)).epsilon(1e-3));
      CHECK(std::abs(phase - std::arg(H)) < 1e-3);
    }
}

TEST_CASE("building: a uniform N-storey building's frequencies are the closed form's, N = 1 to 60", "[excitation][building]") {
  for (int N = 1; N <= 60; ++N) {
    const double m = 2.5e5;
    const ShearBuilding b = ShearBuilding::uniform(N, 0.1 * N, 0.02, m);
    const auto modes = furniture_fem::building_modes(b);
    const double k = b.storey_stiffness[0];
    REQUIRE(modes.omega.size() == N);
    CHECK(modes.omega[0] == Approx(2 * kPi / (0.1 * N)).epsilon(1e-12));
    for (int j = 1; j <= N; ++j) {
      const double closed = 2 * std::sqrt(k / m) * std::sin((2 * j - 1) * kPi / (2.0 * (2 * N + 1)));
      INFO("N " << N << " mode " << j);
      CHECK(modes.omega[j - 1] == Approx(closed).epsilon(1e-9));
    }
    // The participations expand the rigid influence vector: sum_j phi_kj G_j = 1 on every floor.
    const Eigen::VectorXd ones = modes.shape * modes.participation;
    CHECK((ones.array() - 1).abs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("building: floor motions match a direct integration in floor coordinates", "[excitation][building]") {
  ShearBuilding b;
  b.floor_mass = {3.0e5, 2.8e5, 2.6e5, 2.5e5, 2.2e5, 1.8e5};
  b.storey_stiffness = {4.0e8, 3.6e8, 3.3e8, 2.9e8, 2.4e8, 1.9e8};
  b.damping_ratio = 0.03;
  b.rayleigh_modes = {1, 3};
  const int n = b.storeys();
  const double dt = 0.01;
  const Record ground = sampled(dt, 12.0, [](double t) {
    return 2.0 * std::sin(2 * kPi * 0.7 * t) + 1.3 * std::sin(2 * kPi * 2.9 * t + 0.4) +
           0.8 * std::sin(2 * kPi * 7.3 * t) * std::exp(-0.3 * t);
  });
  // Independent: M, K and Rayleigh's C in floor coordinates; a0, a1 from the two modes' frequencies.
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {  // floor i: its storey below and the one above
    M(i, i) = b.floor_mass[i];
    K(i, i) = b.storey_stiffness[i] + (i + 1 < n ? b.storey_stiffness[i + 1] : 0.0);
    if (i + 1 < n) K(i, i + 1) = K(i + 1, i) = -b.storey_stiffness[i + 1];
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);
  const double w1 = std::sqrt(eig.eigenvalues()[0]), w3 = std::sqrt(eig.eigenvalues()[2]), z = b.damping_ratio;
  const double a1 = 2 * z / (w1 + w3), a0 = a1 * w1 * w3;
  const Eigen::MatrixXd C = a0 * M + a1 * K, Minv = M.inverse();
  // RK4 on y = [u, u'] with the ground's piecewise-linear acceleration.
  const auto rate = [&](double t, const Eigen::VectorXd& y) {
    Eigen::VectorXd d(2 * n);
    d.head(n) = y.tail(n);
    d.tail(n) = -Minv * (K * y.head(n) + C * y.tail(n)) - Eigen::VectorXd::Constant(n, ground.value_at(t));
    return d;
  };
  const int sub = 50;
  const double h = dt / sub;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n);
  std::vector<Eigen::VectorXd> absolute(ground.size(), Eigen::VectorXd::Zero(n));
  for (std::size_t i = 0; i + 1 < ground.size(); ++i) {
    for (int s = 0; s < sub; ++s) {
      const double t = ground.time(i) + s * h;
      const Eigen::VectorXd k1 = rate(t, y), k2 = rate(t + h / 2, y + h / 2 * k1), k3 = rate(t + h / 2, y + h / 2 * k2),
                            k4 = rate(t + h, y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    absolute[i + 1] = -Minv * (K * y.head(n) + C * y.tail(n));  // a_g + u''
  }
  for (int floor = 1; floor <= n; ++floor) {
    const Record r = furniture_fem::storey_motion(b, floor, ground);
    REQUIRE(r.size() == ground.size());
    double worst = 0, peak = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      worst = std::max(worst, std::abs(r.acc[i] - absolute[i][floor - 1]));
      peak = std::max(peak, std::abs(absolute[i][floor - 1]));
    }
    INFO("floor " << floor << ": largest difference " << worst << " m/s^2 against a peak of " << peak);
    CHECK(worst < 1e-6 * peak);
    CHECK(peak > 1.0);  // the floors do move
  }
  CHECK(furniture_fem::storey_motion(b, 0, ground).acc == ground.acc);  // floor 0: the ground
}

TEST_CASE("building: bad buildings and floors are refused, naming the key, the index and the value", "[excitation][building]") {
  using Catch::Matchers::Contains;
  const Record ground = sampled(0.01, 1.0, [](double t) { return t; });
  ShearBuilding b = ShearBuilding::uniform(3, 0.5, 0.02);
  CHECK_THROWS_WITH(furniture_fem::storey_motion(b, 4, ground), Contains("floor = 4") && Contains("0 (the ground) to 3"));
  CHECK_THROWS_WITH(furniture_fem::storey_motion(b, -1, ground), Contains("floor = -1"));
  b.floor_mass[1] = -2;
  CHECK_THROWS_WITH(furniture_fem::building_modes(b), Contains("floor_mass[1] = -2"));
  b.floor_mass[1] = 1;
  b.storey_stiffness[2] = std::nan("");
  CHECK_THROWS_WITH(furniture_fem::building_modes(b), Contains("storey_stiffness[2] = nan"));
  b.storey_stiffness.pop_back();
  CHECK_THROWS_WITH(furniture_fem::building_modes(b), Contains("2 values for 3 floors"));
  b = ShearBuilding::uniform(3, 0.5, 0.02);
  b.rayleigh_modes = {2, 2};
  CHECK_THROWS_WITH(furniture_fem::building_modes(b), Contains("rayleigh_modes = [2, 2]"));
  b.rayleigh_modes = {0, 0};
  b.damping_ratio = 1.0;
  CHECK_THROWS_WITH(furniture_fem::building_modes(b), Contains("damping_ratio = 1"));
  CHECK_THROWS_WITH(ShearBuilding::uniform(0, 1.0, 0.02), Contains("storeys = 0"));
  CHECK_THROWS_WITH(ShearBuilding::uniform(5, -1.0, 0.02), Contains("first_period = -1"));
}

}  // namespace building_tests
