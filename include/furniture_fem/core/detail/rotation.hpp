#pragma once
// Rotation helpers: the exponential and logarithm maps of SO(3) (Rodrigues), and the rigid rotation
// that best maps one point cloud onto another (Kabsch). Nodal rotations are stored as matrices and
// updated by spatial rotation increments: R <- exp(dtheta) R.
#ifndef FURNITURE_FEM_CORE_INTERNAL
#error "furniture_fem/core/detail/rotation.hpp is internal: include <furniture_fem/core/simulation.hpp>"
#endif
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "../dense_kernels.hpp"

namespace furniture_fem::detail {

inline Eigen::Matrix3d skew(const Eigen::Vector3d& w) {
  Eigen::Matrix3d S;
  S << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return S;
}

inline Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& w) {
  const double th2 = w.squaredNorm();
  const Eigen::Matrix3d S = skew(w);
  double a, b;
  if (th2 < 1e-12) {  // series: sin(t)/t and (1 - cos t)/t^2 near zero
    a = 1.0 - th2 / 6.0;
    b = 0.5 - th2 / 24.0;
  } else {
    const double th = std::sqrt(th2);
    a = std::sin(th) / th;
    b = (1.0 - std::cos(th)) / th2;
  }
  return Eigen::Matrix3d::Identity() + a * S + b * S * S;
}

// Rotation vector of R (angle in [0, pi]). Uses the quaternion route, which stays accurate near pi.
inline Eigen::Vector3d rotation_log(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  const Eigen::Vector3d v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;  // small angle: theta ~ 2 sin(theta/2)
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

// Best rotation Q with x_i - xc ~ Q (X_i - Xc) (Kabsch), for the factorisation reuse of a rotating body.
template <class Fn>
Eigen::Matrix3d best_rotation(int n, Fn&& pair_of_point, const Eigen::Vector3d& Xc, const Eigen::Vector3d& xc) {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const auto [X, x] = pair_of_point(i);
    H += (x - xc) * (X - Xc).transpose();
  }
  return kabsch_rotation(H);
}

}  // namespace furniture_fem::detail
