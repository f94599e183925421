#pragma once
// furniture_fem/core/integrators.hpp: time-integration policies and their steppers.
//
// Every implicit scheme here is one member of the generalized-alpha family (Chung & Hulbert 1993):
//   M a_{n+1-am} + C v_{n+1-af} + f_int(u_{n+1-af}) = f_ext(t_{n+1-af}),
//   u_{n+1} = u_n + dt v_n + dt^2 ((1/2 - beta) a_n + beta a_{n+1}),
//   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1}).
// Newmark is am = af = 0. As in Boost.Odeint, the scheme is a stepper and the Simulation a system: a
// policy makes a stepper for a step length (`stepper(dt)`), and the stepper owns that dt and every formula
// of the scheme (the predictor and the update of velocities and accelerations from the displacement
// increment, where the balance is enforced, the effective matrix's coefficients, and how a step reaches
// equilibrium), while the Simulation provides the residual, the tangent and the contact.
// See docs/core/concept_integrator.md.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <concepts>
#include <string>
#include <string_view>

#include "errors.hpp"
#include "step_length.hpp"

namespace furniture_fem {

struct IntegratorCoefficients {
  double alpha_m = 0, alpha_f = 0, beta = 0.25, gamma = 0.5;
};

// Carry the unbalanced force into the next step, or iterate until the residual is small.
enum class EquilibriumMode { carry_over, iterate };

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
// scheme reads (max_iterations, tolerance, check_finite); StepSystemArchetype below lists them.
//
// Carry-over: one solve per body; the contact forces applied over the step are those of the predictor
// and the unbalance left by the solve enters the next step's residual, so neither the contact forces
// nor the residual are evaluated again (half the contact cost), and each body is done in one go. The
// contact is then evaluated at the step's end, where the next step starts from.
struct CarryOverScheme {
  template <class Steps>
  static StepInfo step(Steps& steps) {
    StepInfo info = steps.solve_and_commit_bodies();
    info.iterations = 1;
    info.converged = true;
    steps.contact_at_end_of_step();
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

// The sweeps a step scheme drives, as the Simulation's step kernel provides them (the system of a
// stepper's do_step, odeint's `system`). Only declared: it names the interface for the concept checks.
struct StepSystemArchetype {
  int max_iterations() const;
  double tolerance() const;
  bool check_finite() const;
  double end_time() const;
  StepInfo solve_and_commit_bodies();  // carry-over: each body's residual, solve, update and commit
  void contact_at_end_of_step();       // carry-over: the contact at the step's end, for the next step
  void evaluate_residuals();
  double residual_norm();
  int update_bodies(bool first_solve);  // a Newton update of every body; returns the refreshed ones
  void contact_at_trial();              // the contact at the current iterate
  int commit_bodies();                  // returns the ASI integration points moved
};

// The generalized-alpha family's stepper for one step length: every formula of the scheme the
// Simulation applies, inlined where it is used. Made by a family policy's stepper(dt), which checks dt
// (step_length.hpp). The Simulation remakes it for an impact's sub-steps.
class AlphaStepper {
 public:
  AlphaStepper(const IntegratorCoefficients& c, EquilibriumMode mode, double dt)
      : c_(c), mode_(mode), dt_(checked_step_length(dt, "integrator")) {}
  double dt() const { return dt_; }
  EquilibriumMode mode() const { return mode_; }
  const IntegratorCoefficients& coefficients() const { return c_; }

  // The effective matrix of a Newton step, K* = stiffness_factor() K_t + mass_factor(c) M with viscous
  // damping C = c M; a contact's tangent (stiffness K, damping C) enters it as
  // stiffness_factor() (K + velocity_factor() C), velocity_factor() being dv_{n+1} / du_{n+1}.
  double stiffness_factor() const { return 1 - c_.alpha_f; }
  double velocity_factor() const { return c_.gamma / (c_.beta * dt_); }
  double mass_factor(double c) const {
    return (1 - c_.alpha_m) / (c_.beta * dt_ * dt_) + (1 - c_.alpha_f) * c_.gamma / (c_.beta * dt_) * c;
  }

  // Predictor and corrector: Newmark's acceleration and velocity at t_{n+1} from the step's increment
  // du, given v_n and a_n (du = 0: the predictor "no motion"). V: any vector (or field) type.
  template <class V>
  struct Rates {
    V acceleration, velocity;
  };
  template <class V>
  Rates<V> update(const V& du, const V& vn, const V& an) const {
    V a = (du - dt_ * vn - dt_ * dt_ * (0.5 - c_.beta) * an) / (c_.beta * dt_ * dt_);
    V v = vn + dt_ * ((1 - c_.gamma) * an + c_.gamma * a);
    return {std::move(a), std::move(v)};
  }
  // The velocity the predictor's contact is evaluated at: v_n + dt a_n (the predictor's Newmark
  // velocity, (1 - gamma / beta) v_n, has the wrong sign, and friction evaluated there pumps energy).
  template <class V>
  V contact_velocity(const V& vn, const V& an) const {
    return vn + dt_ * an;
  }

  // Where the balance is enforced: x_{n+1-am} for the inertia, x_{n+1-af} for the forces and the
  // damping velocity (x1 at t_{n+1}, x0 at t_n).
  template <class V>
  V at_inertia_point(const V& x1, const V& x0) const {
    return (1 - c_.alpha_m) * x1 + c_.alpha_m * x0;
  }
  template <class V>
  V at_force_point(const V& x1, const V& x0) const {
    return (1 - c_.alpha_f) * x1 + c_.alpha_f * x0;
  }
  // The end force's share in the step's impulse, M (v1 - v0) = dt ((1 - s) f0 + s f1): gamma.
  double end_force_share() const { return c_.gamma; }

  // One step on the system: carry-over or iterated equilibrium (the policy's mode).
  template <class System>
  StepInfo do_step(System& system) const {
    return mode_ == EquilibriumMode::carry_over ? CarryOverScheme::step(system) : IteratedScheme::step(system);
  }

 private:
  IntegratorCoefficients c_;
  EquilibriumMode mode_;
  double dt_;
};

// What the Simulation asks of a stepper (AlphaStepper is the reference). The vector type of the
// checks is a node's six DOFs; the Simulation also applies update, contact_velocity and the
// balance points to 3-vectors and to a rigid body's affine fields. Copyable: the Simulation assigns a
// new one when the step length changes.
template <class S>
concept Stepper = std::copyable<S> &&
    requires(const S& s, const Eigen::Matrix<double, 6, 1>& x, double c, StepSystemArchetype& system) {
      { s.dt() } -> std::same_as<double>;
      { s.stiffness_factor() } -> std::same_as<double>;
      { s.velocity_factor() } -> std::same_as<double>;
      { s.mass_factor(c) } -> std::same_as<double>;
      { s.update(x, x, x).acceleration } -> std::convertible_to<Eigen::Matrix<double, 6, 1>>;
      { s.update(x, x, x).velocity } -> std::convertible_to<Eigen::Matrix<double, 6, 1>>;
      { s.contact_velocity(x, x) } -> std::convertible_to<Eigen::Matrix<double, 6, 1>>;
      { s.at_inertia_point(x, x) } -> std::convertible_to<Eigen::Matrix<double, 6, 1>>;
      { s.at_force_point(x, x) } -> std::convertible_to<Eigen::Matrix<double, 6, 1>>;
      { s.end_force_share() } -> std::same_as<double>;
      { s.do_step(system) } -> std::same_as<StepInfo>;
    };

// An integrator policy: makes its stepper for a step length, and names itself.
template <class I>
concept IntegratorPolicy = requires(const I& i, double dt) {
  { i.stepper(dt) } -> Stepper;
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
  AlphaStepper stepper(double dt) const { return {coefficients(), mode, dt}; }
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
  AlphaStepper stepper(double dt) const { return {coefficients(), mode, dt}; }
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
  AlphaStepper stepper(double dt) const { return {coefficients(), mode, dt}; }
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
  AlphaStepper stepper(double dt) const { return {coef, mode, dt}; }
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

template <class I>
constexpr bool check_integrator_policy() {
  static_assert(IntegratorPolicy<I>,
                "furniture_fem: the Integrator policy must provide stepper(double dt) returning a Stepper (dt(), "
                "stiffness_factor(), velocity_factor(), mass_factor(c), update(du, vn, an), contact_velocity(vn, an), "
                "at_inertia_point, at_force_point, end_force_share(), do_step(system); AlphaStepper is one) and "
                "name(); see docs/core/concept_integrator.md");
  return true;
}

}  // namespace furniture_fem
