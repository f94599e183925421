#pragma once
// Internal: mass and centre-of-gravity calibration of a body by member densities.
// Users include furniture_fem/furniture/furniture.hpp, not this file.
//
// The paper matched each item's centre of gravity (Table 2) "by adjusting the member densities".
// Which densities is left open; we scale every element's line mass by a smooth positive factor
//
//     s_e = exp(lambda . phi_e),   phi_e = (1, x_e, y_e, z_e)   (element mid point, item frame),
//
// and solve the four conditions mass = M and centre = (x_t, y_t, z_t) for lambda by Newton's method.
// This is the least-change solution in the relative-entropy sense: it is uniform scaling when the
// geometry already has the right centre, it never produces a negative density (a linear field
// a + b z + c y can), and it exists whenever the target lies inside the convex hull of the element mid
// points. The dual objective sum(m_e s_e) - lambda . T is convex, so damped Newton converges.
#ifndef FURNITURE_FEM_FURNITURE_INTERNAL
#error "furniture_fem/furniture/detail/furniture_calibration.hpp is internal: include <furniture_fem/furniture/furniture.hpp>"
#endif
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "../../core/dense_kernels.hpp"
#include "../../core/model.hpp"

namespace furniture_fem {

// What the calibration of one body aimed at and reached. Positions are in the item frame (x along
// the width, y along the depth with the front at -D/2, z up from the item's base).
struct MassCalibration {
  double target_mass = 0, mass = 0;                    // kg
  Vec3 target_cog = Vec3::Zero(), cog = Vec3::Zero();  // m, item frame
  double min_factor = 1, max_factor = 1;               // extreme factors applied to the initial line masses
};

namespace detail {

// Scales the line masses of `body` (positions mapped to the item frame by x_local = R^T (X - p)) so
// that its mass is `mass` and its centre of gravity `cog_local`. Throws ModelError naming `who` when
// no positive density field reaches the target.
inline MassCalibration calibrate_mass(Model& model, int body, const Mat3& R, const Vec3& p, double mass,
                                      const Vec3& cog_local, const std::string& who) {
  if (!(mass > 0) || !std::isfinite(mass))
    throw ModelError(who + ": target mass must be positive (got " + fmt(mass) + " kg)");
  const auto& elements = model.body(body).elements;
  const int n = static_cast<int>(elements.size());
  std::vector<double> m0(n);
  std::vector<Vec3> c(n);
  double m_total = 0, extent = 0;
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k < n; ++k) {
    const auto& el = model.elements()[elements[k]];
    m0[k] = el.line_mass * model.element_length(elements[k]);
    c[k] = R.transpose() * (0.5 * (model.node(el.n1).X + model.node(el.n2).X) - p);
    m_total += m0[k];
    centre += m0[k] * c[k];
  }
  if (!(m_total > 0)) throw ModelError(who + ": body has no mass to calibrate");
  centre /= m_total;
  for (int k = 0; k < n; ++k) extent = std::max(extent, (c[k] - centre).cwiseAbs().maxCoeff());
  extent = std::max(extent, 1e-3);

  // Centred and scaled features keep the 4 x 4 Newton system well conditioned.
  using Vec4 = Eigen::Vector4d;
  using Mat4 = Eigen::Matrix4d;
  std::vector<Vec4> phi(n);
  for (int k = 0; k < n; ++k) phi[k] << 1.0, (c[k] - centre) / extent;
  Vec4 target;
  target << 1.0, (cog_local - centre) / extent;
  target *= mass;

  Vec4 lambda(std::log(mass / m_total), 0, 0, 0);
  auto objective = [&](const Vec4& l) {
    double f = 0;
    for (int k = 0; k < n; ++k) f += m0[k] * std::exp(l.dot(phi[k]));
    return f - l.dot(target);
  };
  bool converged = false;
  double f = objective(lambda);
  for (int it = 0; it < 200 && !converged; ++it) {
    Vec4 g = -target;
    Mat4 H = Mat4::Zero();
    for (int k = 0; k < n; ++k) {
      const double w = m0[k] * std::exp(lambda.dot(phi[k]));
      g += w * phi[k];
      H += w * phi[k] * phi[k].transpose();
    }
    // 1e-10 relative: far below the 0.5 % asked of the calibration, well above the round-off of the sums.
    if (g.cwiseAbs().maxCoeff() <= 1e-10 * mass) {
      converged = true;
      break;
    }
    const Vec4 step = -detail::ldlt_solve(H, g);
    // Backtracking keeps the convex dual decreasing; the last term lets the final Newton steps through
    // once the decrease is below the round-off of f itself.
    double a = 1.0;
    Vec4 trial = lambda + step;
    double f_trial = objective(trial);
    while (!(f_trial <= f + 1e-4 * a * g.dot(step) + 1e-14 * std::abs(f)) && a > 1e-12) {
      a *= 0.5;
      trial = lambda + a * step;
      f_trial = objective(trial);
    }
    if (a <= 1e-12) break;
    lambda = trial;
    f = f_trial;
  }
  MassCalibration out;
  out.target_mass = mass;
  out.target_cog = cog_local;
  out.min_factor = std::numeric_limits<double>::infinity();
  out.max_factor = 0;
  if (!converged)
    throw ModelError(who + ": the centre of gravity (" + fmt(cog_local.x()) + ", " + fmt(cog_local.y()) + ", " +
                     fmt(cog_local.z()) + ") m in the item frame cannot be reached with positive member "
                     "densities (it must lie inside the hull of the members)");
  for (int k = 0; k < n; ++k) {
    const double s = std::exp(lambda.dot(phi[k]));
    const int e = elements[k];
    model.set_line_mass(e, model.elements()[e].line_mass * s);
    out.min_factor = std::min(out.min_factor, s);
    out.max_factor = std::max(out.max_factor, s);
  }
  out.mass = model.body_mass(body);
  out.cog = R.transpose() * (model.body_centre_of_gravity(body) - p);
  return out;
}

}  // namespace detail
}  // namespace furniture_fem
