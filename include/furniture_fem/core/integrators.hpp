#pragma once
// furniture_fem/core/integrators.hpp: time-integration policies.
//
// Every implicit scheme here is one member of the generalized-alpha family (Chung & Hulbert 1993):
//   M a_{n+1-am} + C v_{n+1-af} + f_int(u_{n+1-af}) = f_ext(t_{n+1-af}),
//   u_{n+1} = u_n + dt v_n + dt^2 ((1/2 - beta) a_n + beta a_{n+1}),
//   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1}).
// Newmark is am = af = 0. A policy is a small value type giving these coefficients, and whether the
// step iterates to equilibrium (Newton with a reused matrix) or carries the unbalanced force into the
// next step (one solve per step, as the paper's group does). See docs/core/concept_integrator.md.
#include <algorithm>
#include <cmath>
#include <complex>
#include <concepts>
#include <string>
#include <string_view>

#include "errors.hpp"

namespace furniture_fem {

struct IntegratorCoefficients {
  double alpha_m = 0, alpha_f = 0, beta = 0.25, gamma = 0.5;

  // What the coefficients make of a step dt (the Simulation uses these, and only these):
  // the factor on the mass in the effective matrix, K_eff = (1 - af) K + mass_factor M, with viscous
  // damping C = c M;
  double mass_factor(double dt, double c) const {
    return (1 - alpha_m) / (beta * dt * dt) + (1 - alpha_f) * gamma / (beta * dt) * c;
  }
  // Newmark's acceleration and velocity at t_{n+1} from the increment du over the step.
  template <class V>
  V acceleration(const V& du, const V& vn, const V& an, double dt) const {
    return (du - dt * vn - dt * dt * (0.5 - beta) * an) / (beta * dt * dt);
  }
  template <class V>
  V velocity(const V& vn, const V& an, const V& a1, double dt) const {
    return vn + dt * ((1 - gamma) * an + gamma * a1);
  }
};

// Carry the unbalanced force into the next step, or iterate until the residual is small.
enum class EquilibriumMode { carry_over, iterate };

template <class I>
concept IntegratorPolicy = requires(const I& i) {
  { i.coefficients() } -> std::same_as<IntegratorCoefficients>;
  { i.mode } -> std::convertible_to<EquilibriumMode>;
  { i.name() } -> std::convertible_to<std::string>;
};

// Newmark's family; presets: paper() (beta 4/9, gamma 5/6) and average_acceleration() (1/4, 1/2).
struct Newmark {
  double beta = 0.25, gamma = 0.5;
  EquilibriumMode mode = EquilibriumMode::carry_over;

  static Newmark paper(EquilibriumMode m = EquilibriumMode::carry_over) { return {4.0 / 9.0, 5.0 / 6.0, m}; }
  static Newmark average_acceleration(EquilibriumMode m = EquilibriumMode::iterate) { return {0.25, 0.5, m}; }

  IntegratorCoefficients coefficients() const {
    if (!(beta > 0) || !(gamma >= 0.5) || !std::isfinite(beta) || !std::isfinite(gamma))
      throw ModelError("Newmark: need beta > 0 and gamma >= 1/2 (got beta = " + std::to_string(beta) +
                       ", gamma = " + std::to_string(gamma) + ")");
    return {0, 0, beta, gamma};
  }
  std::string name() const {
    return "Newmark (beta " + std::to_string(beta) + ", gamma " + std::to_string(gamma) + ")";
  }
  // Spectral radius of the one-step map of x'' + omega^2 x = 0 at omega dt = w (see below).
  double spectral_radius(double w) const;
};

// Generalized-alpha with user spectral radius at infinity rho_inf in [0, 1] (1: no damping).
struct GeneralizedAlpha {
  double rho_inf = 0.8;
  EquilibriumMode mode = EquilibriumMode::iterate;
  IntegratorCoefficients coefficients() const {
    if (!(rho_inf >= 0 && rho_inf <= 1))
      throw ModelError("GeneralizedAlpha: rho_inf must lie in [0, 1] (got " + std::to_string(rho_inf) + ")");
    IntegratorCoefficients c;
    c.alpha_m = (2 * rho_inf - 1) / (rho_inf + 1);
    c.alpha_f = rho_inf / (rho_inf + 1);
    c.gamma = 0.5 - c.alpha_m + c.alpha_f;
    c.beta = 0.25 * (1 - c.alpha_m + c.alpha_f) * (1 - c.alpha_m + c.alpha_f);
    return c;
  }
  std::string name() const { return "generalized-alpha (rho_inf " + std::to_string(rho_inf) + ")"; }
};

// HHT-alpha (Hilber-Hughes-Taylor), alpha in [-1/3, 0]: generalized-alpha with am = 0.
struct HhtAlpha {
  double alpha = -0.1;
  EquilibriumMode mode = EquilibriumMode::iterate;
  IntegratorCoefficients coefficients() const {
    if (!(alpha >= -1.0 / 3.0 && alpha <= 0))
      throw ModelError("HhtAlpha: alpha must lie in [-1/3, 0] (got " + std::to_string(alpha) + ")");
    return {0, -alpha, 0.25 * (1 - alpha) * (1 - alpha), 0.5 - alpha};
  }
  std::string name() const { return "HHT-alpha (alpha " + std::to_string(alpha) + ")"; }
};

// Any member of the family chosen at run time (a scene file, a parameter study): one type, so a
// program that lets its user pick the scheme compiles the solver once.
struct RuntimeIntegrator {
  IntegratorCoefficients coef;
  EquilibriumMode mode = EquilibriumMode::carry_over;
  std::string label = "runtime";
  template <class I>
  static RuntimeIntegrator from(const I& i) {
    return {i.coefficients(), i.mode, i.name()};
  }
  IntegratorCoefficients coefficients() const { return coef; }
  std::string name() const { return label; }
};

// Spectral radius of a generalized-alpha scheme for x'' + omega^2 x = 0 at omega dt = w: the largest
// eigenvalue modulus of the one-step map on (x, v dt, a dt^2), built by stepping the three unit states.
inline double spectral_radius(const IntegratorCoefficients& c, double w) {
  // Unknown a1 from: (1-am) a1 + am a0 + w^2 ((1-af) x1 + af x0) = 0, with
  // x1 = x0 + v0 + (1/2 - beta) a0 + beta a1 (units dt = 1).
  double A[3][3];
  for (int k = 0; k < 3; ++k) {
    const double x0 = k == 0, v0 = k == 1, a0 = k == 2;
    const double xpred = x0 + v0 + (0.5 - c.beta) * a0;
    const double a1 = -(c.alpha_m * a0 + w * w * ((1 - c.alpha_f) * xpred + c.alpha_f * x0)) /
                      ((1 - c.alpha_m) + w * w * (1 - c.alpha_f) * c.beta);
    A[0][k] = xpred + c.beta * a1;
    A[1][k] = v0 + (1 - c.gamma) * a0 + c.gamma * a1;
    A[2][k] = a1;
  }
  // Characteristic polynomial l^3 - I1 l^2 + I2 l - I3; its roots by Durand-Kerner iteration.
  const double I1 = A[0][0] + A[1][1] + A[2][2];
  const double I2 = A[0][0] * A[1][1] - A[0][1] * A[1][0] + A[0][0] * A[2][2] - A[0][2] * A[2][0] +
                    A[1][1] * A[2][2] - A[1][2] * A[2][1];
  const double I3 = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                    A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                    A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  using C = std::complex<double>;
  C r[3] = {C(0.4, 0.9), C(0.4, 0.9) * C(0.4, 0.9), C(0.4, 0.9) * C(0.4, 0.9) * C(0.4, 0.9)};
  auto p = [&](C l) { return ((l - I1) * l + I2) * l - I3; };
  for (int it = 0; it < 500; ++it)
    for (int i = 0; i < 3; ++i) {
      C den = 1;
      for (int j = 0; j < 3; ++j)
        if (j != i) den *= (r[i] - r[j]);
      r[i] -= p(r[i]) / den;
    }
  return std::max({std::abs(r[0]), std::abs(r[1]), std::abs(r[2])});
}

inline double Newmark::spectral_radius(double w) const { return furniture_fem::spectral_radius(coefficients(), w); }

// What one step did: Newton iterations, the relative residual left (carried over if not iterated),
// bodies whose matrix was refreshed, ASI integration points moved.
struct StepInfo {
  int iterations = 0;
  double residual = 0;
  bool converged = true;
  int refreshed_bodies = 0;
  int shifted_points = 0;
};

// How a step reaches equilibrium (the integrator's EquilibriumMode). A scheme orders the Simulation's
// sweeps over the bodies; `Steps` is the Simulation's step kernel: the sweeps, and the options a
// scheme reads (max_iterations, tolerance, check_finite).
//
// Carry-over: one solve per body; the contact forces applied over the step are those of the predictor
// and the unbalance left by the solve enters the next step's residual, so neither the contact forces
// nor the residual are evaluated again (half the contact cost), and each body is done in one go.
struct CarryOverScheme {
  template <class Steps>
  static StepInfo step(Steps& steps) {
    StepInfo info = steps.solve_and_commit_bodies();
    info.iterations = 1;
    info.converged = true;
    return info;
  }
};

// Iterated equilibrium: Newton with each body's matrix reused, contact re-evaluated at every
// iterate, until the relative residual is below the tolerance (or max_iterations); then commit.
struct IteratedScheme {
  template <class Steps>
  static StepInfo step(Steps& steps) {
    StepInfo info;
    steps.evaluate_residuals();
    double rel = steps.residual_norm();
    info.residual = rel;
    for (int it = 0; it < steps.max_iterations(); ++it) {
      info.refreshed_bodies += steps.update_bodies(it == 0);
      steps.contact_at_trial();
      steps.evaluate_residuals();
      rel = steps.residual_norm();
      info.iterations = it + 1;
      info.residual = rel;
      if (steps.check_finite() && !std::isfinite(rel))
        throw SimulationError(steps.end_time(), "the residual is not finite (NaN or infinity) after iteration " +
                                                    std::to_string(it + 1) + ": the step diverged; try a smaller dt");
      if (rel < steps.tolerance()) break;
    }
    info.converged = rel < steps.tolerance();
    info.shifted_points = steps.commit_bodies();
    return info;
  }
};

// The scheme of a mode.
template <class Steps>
StepInfo step_with(EquilibriumMode mode, Steps& steps) {
  return mode == EquilibriumMode::carry_over ? CarryOverScheme::step(steps) : IteratedScheme::step(steps);
}

template <class I>
constexpr bool check_integrator_policy() {
  static_assert(IntegratorPolicy<I>,
                "furniture_fem: the Integrator policy must provide coefficients() -> IntegratorCoefficients, "
                "a data member `mode` (EquilibriumMode) and name(); see docs/core/concept_integrator.md");
  return true;
}

}  // namespace furniture_fem
