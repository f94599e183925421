#pragma once
// furniture_fem/excitation/building.hpp: the floor motion of a storey of a linear shear building under
// a ground record (issue 50): a room on storey k of a tall building shakes with that floor's absolute
// acceleration, not the ground's. Part of furniture_fem/excitation/excitation.hpp; SI units throughout.
//
// The building: N lumped floor masses m_i on storeys of lateral stiffness k_i (storey i joins floor
// i - 1 to floor i; floor 0 is the ground), classically damped (a damping ratio per mode: one for all,
// or Rayleigh's a0 / (2 w) + a1 w / 2 through two modes). Its floor motions are the modes' sum,
//   q_j'' + 2 zeta_j w_j q_j' + w_j^2 q_j = -G_j a_g(t),  G_j = phi_j^T M 1 (phi_j mass-normalised),
// each mode stepped by the exact recurrence for a piecewise-linear input (the ground record between its
// samples; detail::gm::SdofStep, the response spectrum's), so the floor's absolute acceleration
//   a_k = a_g + u_k'' = -sum_j phi_kj (2 zeta_j w_j q_j' + w_j^2 q_j)
// is exact at the record's samples (sum_j phi_kj G_j = 1: the ground term cancels). Docs:
// docs/excitation/building.md.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "../core/dense_kernels.hpp"
#include "../core/errors.hpp"
#include "record_io.hpp"
#define FURNITURE_FEM_EXCITATION_INTERNAL
#include "detail/excitation_dsp.hpp"
#undef FURNITURE_FEM_EXCITATION_INTERNAL

namespace furniture_fem {

// A linear shear building, floors bottom up (floor 1 above the ground storey).
struct ShearBuilding {
  std::vector<double> floor_mass;         // kg, per floor 1..N
  std::vector<double> storey_stiffness;   // N/m, storey i joins floor i - 1 and floor i
  // Damping ratio of every mode (modal damping), or, when rayleigh_modes is set, the ratio Rayleigh
  // damping has at those two modes (1-based; the other modes follow a0 / (2 w) + a1 w / 2).
  double damping_ratio = 0.02;
  std::array<int, 2> rayleigh_modes = {0, 0};
  int storeys() const { return static_cast<int>(floor_mass.size()); }

  // N equal floors and storeys whose first period is T1 (s): k / m from
  // w_1 = 2 sqrt(k / m) sin(pi / (2 (2N + 1))). The floor mass only scales forces (1 kg by default).
  static ShearBuilding uniform(int storeys, double first_period, double damping_ratio, double floor_mass = 1.0);
};

// Natural circular frequencies (ascending), mass-normalised mode shapes (columns, floors 1..N), each
// mode's participation G_j = phi_j^T M 1 and its damping ratio.
struct BuildingModes {
  Eigen::VectorXd omega;
  Eigen::MatrixXd shape;
  Eigen::VectorXd participation;
  Eigen::VectorXd damping_ratio;
};

namespace detail::building {

inline std::string num(double v) { return detail::gm::num(v); }

inline void check(const ShearBuilding& b) {
  const auto bad = [](const std::string& key, int i, double v, const char* what) {
    throw InputError("building: " + key + "[" + std::to_string(i) + "] = " + num(v) + ": " + what);
  };
  const int n = b.storeys();
  if (n < 1) throw InputError("building: no floors (floor_mass is empty)");
  if (static_cast<int>(b.storey_stiffness.size()) != n)
    throw InputError("building: storey_stiffness has " + std::to_string(b.storey_stiffness.size()) +
                     " values for " + std::to_string(n) + " floors (one per storey)");
  for (int i = 0; i < n; ++i) {
    if (!(b.floor_mass[i] > 0) || !std::isfinite(b.floor_mass[i])) bad("floor_mass", i, b.floor_mass[i], "must be a positive mass (kg)");
    if (!(b.storey_stiffness[i] > 0) || !std::isfinite(b.storey_stiffness[i]))
      bad("storey_stiffness", i, b.storey_stiffness[i], "must be a positive stiffness (N/m)");
  }
  if (!(b.damping_ratio >= 0 && b.damping_ratio < 1))
    throw InputError("building: damping_ratio = " + num(b.damping_ratio) + ": must lie in [0, 1)");
  const auto [r1, r2] = b.rayleigh_modes;
  if ((r1 != 0 || r2 != 0) && !(r1 >= 1 && r2 > r1 && r2 <= n))
    throw InputError("building: rayleigh_modes = [" + std::to_string(r1) + ", " + std::to_string(r2) +
                     "]: two modes 1 <= i < j <= " + std::to_string(n) + " (or none: modal damping)");
}

}  // namespace detail::building

inline ShearBuilding ShearBuilding::uniform(int storeys, double first_period, double damping_ratio, double floor_mass) {
  if (storeys < 1) throw InputError("building: storeys = " + std::to_string(storeys) + ": at least 1");
  if (!(first_period > 0) || !std::isfinite(first_period))
    throw InputError("building: first_period = " + detail::building::num(first_period) + ": must be a positive period (s)");
  const double w1 = 2 * detail::gm::kPi / first_period;
  const double s = 2 * std::sin(detail::gm::kPi / (2.0 * (2 * storeys + 1)));
  const double k = floor_mass * (w1 / s) * (w1 / s);
  ShearBuilding b;
  b.floor_mass.assign(storeys, floor_mass);
  b.storey_stiffness.assign(storeys, k);
  b.damping_ratio = damping_ratio;
  detail::building::check(b);
  return b;
}

// The building's modes: K phi = w^2 M phi through the symmetric M^-1/2 K M^-1/2 (tridiagonal).
[[nodiscard]] inline BuildingModes building_modes(const ShearBuilding& b) {
  detail::building::check(b);
  const int n = b.storeys();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {  // storey i joins floor i - 1 (the ground for i = 0) and floor i
    const double k = b.storey_stiffness[i];
    K(i, i) += k;
    if (i > 0) {
      K(i - 1, i - 1) += k;
      K(i - 1, i) -= k;
      K(i, i - 1) -= k;
    }
  }
  Eigen::VectorXd s(n);  // M^-1/2
  for (int i = 0; i < n; ++i) s[i] = 1 / std::sqrt(b.floor_mass[i]);
  const detail::SymmetricEigen eig = detail::symmetric_eigen(Eigen::MatrixXd(s.asDiagonal() * K * s.asDiagonal()));
  BuildingModes m;
  m.omega = eig.values.cwiseMax(0).cwiseSqrt();
  m.shape = s.asDiagonal() * eig.vectors;  // phi^T M phi = I
  Eigen::VectorXd M1(n);
  for (int i = 0; i < n; ++i) M1[i] = b.floor_mass[i];
  m.participation = m.shape.transpose() * M1;
  m.damping_ratio = Eigen::VectorXd::Constant(n, b.damping_ratio);
  if (const auto [r1, r2] = b.rayleigh_modes; r1 > 0) {
    // zeta at w_i and w_j: a0 / (2 w) + a1 w / 2 = zeta at both.
    const double wi = m.omega[r1 - 1], wj = m.omega[r2 - 1], z = b.damping_ratio;
    const double a0 = 2 * z * wi * wj / (wi + wj), a1 = 2 * z / (wi + wj);
    for (int j = 0; j < n; ++j) {
      m.damping_ratio[j] = a0 / (2 * m.omega[j]) + a1 * m.omega[j] / 2;
      if (!(m.damping_ratio[j] < 1))  // the exact step is for underdamped modes
        throw InputError("building: Rayleigh damping of " + detail::building::num(z) + " at modes " +
                         std::to_string(r1) + " and " + std::to_string(r2) + " overdamps mode " + std::to_string(j + 1) +
                         " (damping ratio " + detail::building::num(m.damping_ratio[j]) +
                         "); use modal damping (no rayleigh_modes) or modes further apart");
    }
  }
  return m;
}

// The absolute acceleration of floor `floor` (1..N; 0: the ground itself) under the ground record, at
// the record's samples (exact for its piecewise-linear motion), from rest. The record keeps its
// samples' times; its name says the floor.
[[nodiscard]] inline Record storey_motion(const ShearBuilding& b, int floor, const Record& ground) {
  detail::gm::check_record(ground, "storey_motion");
  const BuildingModes m = building_modes(b);
  if (floor < 0 || floor > b.storeys())
    throw InputError("building: floor = " + std::to_string(floor) + ": must be 0 (the ground) to " +
                     std::to_string(b.storeys()) + " (the roof)");
  Record out = ground;
  out.name = ground.name + ", floor " + std::to_string(floor) + " of " + std::to_string(b.storeys());
  if (floor == 0) return out;
  std::fill(out.acc.begin(), out.acc.end(), 0.0);
  for (int j = 0; j < b.storeys(); ++j) {
    const double w = m.omega[j], z = m.damping_ratio[j], G = m.participation[j], phi = m.shape(floor - 1, j);
    if (phi == 0 || G == 0) continue;
    const detail::gm::SdofStep step(w, z, ground.dt);
    double q = 0, v = 0;  // per unit participation: q_j = G u
    for (std::size_t i = 0; i + 1 < ground.acc.size(); ++i) {
      step.advance(q, v, ground.acc[i], ground.acc[i + 1]);
      out.acc[i + 1] -= phi * G * (2 * z * w * v + w * w * q);
    }
  }
  return out;  // acc[0] = 0: at rest the floor's absolute acceleration is the modes' restoring forces, none
}

}  // namespace furniture_fem
