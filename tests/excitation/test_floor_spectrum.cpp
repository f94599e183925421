// A floor response spectrum (storey_motion, then response_spectrum) against an independent
// computation: the whole building and an oscillator standing on floor k integrated as one linear ODE
// system by RK4, in floor coordinates, with no modes and no exact recurrence:
//   M u'' + C u' + K u = -M 1 a_g,   a_k = a_g + u_k'',   s'' + 2 zeta w s' + w^2 s = -a_k,
// the oscillator's absolute acceleration -(2 zeta w s' + w^2 s); C = a0 M + a1 K (Rayleigh damping
// through modes 1 and 3, a0 and a1 from the closed-form frequencies of a uniform building). The
// oscillator is light (no feedback on the floor): what a floor response spectrum means.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include <furniture_fem/excitation/building.hpp>
#include <furniture_fem/excitation/spectrum.hpp>
#include <furniture_fem/excitation/synthetic.hpp>

namespace floor_spectrum_tests {  // this file's own names (its group compiles files in batches)

namespace {

using furniture_fem::Record;
using furniture_fem::ShearBuilding;
constexpr double kPi = 3.14159265358979323846;

// Peak |absolute acceleration| of an oscillator (period T, damping zeta) on floor `floor` of b, by RK4
// at `substeps` steps per sample of the ground record (read linearly between its samples).
double rk4_floor_peak(const ShearBuilding& b, const Eigen::MatrixXd& C, int floor, const Record& g, double T,
                      double zeta, int substeps) {
  const int n = b.storeys();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    K(i, i) += b.storey_stiffness[i];
    if (i + 1 < n) {
      K(i, i) += b.storey_stiffness[i + 1];
      K(i, i + 1) = K(i + 1, i) = -b.storey_stiffness[i + 1];
    }
  }
  Eigen::VectorXd m_inv(n);
  for (int i = 0; i < n; ++i) m_inv[i] = 1 / b.floor_mass[i];
  const double w = 2 * kPi / T;
  // State: u (n), u' (n), s, s'.
  const auto rhs = [&](const Eigen::VectorXd& y, double ag) {
    Eigen::VectorXd d(2 * n + 2);
    const auto u = y.head(n), v = y.segment(n, n);
    const Eigen::VectorXd acc = ((-(m_inv.asDiagonal() * (C * v + K * u))).array() - ag).matrix();
    d.head(n) = v;
    d.segment(n, n) = acc;
    const double a_floor = ag + acc[floor - 1];
    d[2 * n] = y[2 * n + 1];
    d[2 * n + 1] = -2 * zeta * w * y[2 * n + 1] - w * w * y[2 * n] - a_floor;
    return d;
  };
  Eigen::VectorXd y = Eigen::VectorXd::Zero(2 * n + 2);
  const double h = g.dt / substeps;
  double peak = 0;
  // The record's samples, then one period at rest (the project's spectrum also follows the record by
  // free vibration, where a short motion's peak may lie).
  const std::size_t tail = static_cast<std::size_t>(std::ceil(T / g.dt)) + 1;
  for (std::size_t i = 0; i + 1 < g.acc.size() + tail; ++i) {
    const double a0 = i < g.acc.size() ? g.acc[i] : 0, a1 = i + 1 < g.acc.size() ? g.acc[i + 1] : 0;
    for (int s = 0; s < substeps; ++s) {
      const auto ag = [&](double f) { return a0 + (a1 - a0) * (s + f) / substeps; };
      const Eigen::VectorXd k1 = rhs(y, ag(0)), k2 = rhs(y + 0.5 * h * k1, ag(0.5)), k3 = rhs(y + 0.5 * h * k2, ag(0.5)),
                            k4 = rhs(y + h * k3, ag(1));
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      peak = std::max(peak, std::abs(2 * zeta * w * y[2 * n + 1] + w * w * y[2 * n]));
    }
  }
  return peak;
}

}  // namespace

TEST_CASE("building: a floor response spectrum against the building and an oscillator integrated as one system",
          "[excitation][building][spectrum]") {
  // 10 storeys, T1 = 1 s, 3 % Rayleigh damping at modes 1 and 3; the oscillator on floor 7.
  const int N = 10, floor = 7;
  const double zeta_b = 0.03;
  ShearBuilding b = ShearBuilding::uniform(N, 1.0, zeta_b);
  b.rayleigh_modes = {1, 3};
  const double k = b.storey_stiffness[0], m = b.floor_mass[0];
  const auto omega = [&](int j) { return 2 * std::sqrt(k / m) * std::sin((2 * j - 1) * kPi / (2.0 * (2 * N + 1))); };
  const double wi = omega(1), wj = omega(3);
  const double a0 = 2 * zeta_b * wi * wj / (wi + wj), a1 = 2 * zeta_b / (wi + wj);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(N, N);  // the C of a0 M + a1 K, formed here
  for (int i = 0; i < N; ++i) {
    K(i, i) += k;
    if (i + 1 < N) K(i, i) += k, K(i, i + 1) = K(i + 1, i) = -k;
  }
  const Eigen::MatrixXd C = a0 * m * Eigen::MatrixXd::Identity(N, N) + a1 * K;

  furniture_fem::SyntheticOptions o;  // a broadband 20 s record at 0.005 s
  o.seed = 7;
  o.duration = 20;
  o.dt = 0.005;
  o.pga = 3.0;
  const Record ground = furniture_fem::synthetic_motion(o);
  const Record floor_motion = furniture_fem::storey_motion(b, floor, ground);
  const std::vector<double> periods{0.3, 0.5, 1.0, 2.0};
  for (const double zeta : {0.05, 0.02}) {
    const auto spectrum = furniture_fem::response_spectrum(floor_motion, periods, zeta);
    for (std::size_t p = 0; p < periods.size(); ++p) {
      // Error budget: the floor motion is exact at the samples and read linearly between them by the
      // spectrum, which attenuates content at the oscillator's period by about (w dt)^2 / 12 (0.15 %
      // at 0.3 s, dt 0.005 s); each peak is sampled at T / 100 (spectrum, <= 0.05 %) and at dt / 20
      // (RK4, < 0.01 %); RK4's own error at (w h)^4 with w h < 0.03 (the top mode) is negligible.
      // So 0.2 %, inside the 1 %. Measured: the spectrum 0.005 % to 0.048 % below RK4.
      const double independent = rk4_floor_peak(b, C, floor, ground, periods[p], zeta, 20);
      INFO("T = " << periods[p] << " s, zeta " << zeta << ": spectrum " << spectrum.sa[p] << ", RK4 " << independent
                  << ", ratio - 1 = " << spectrum.sa[p] / independent - 1);
      CHECK(spectrum.sa[p] == Approx(independent).epsilon(0.002));
    }
  }
  // The floor amplifies the ground near the building's first period: the test is not of a quiet floor.
  const auto at_t1 = furniture_fem::response_spectrum(floor_motion, {1.0}, 0.05).sa[0];
  const auto ground_t1 = furniture_fem::response_spectrum(ground, {1.0}, 0.05).sa[0];
  CHECK(at_t1 > 2 * ground_t1);
}

}  // namespace floor_spectrum_tests
