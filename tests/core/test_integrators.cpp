// Integrator policies: the generalized-alpha family's coefficients and spectral radii, the
// Simulation's time stepping against spectral_radius() and the convergence order, and the explicit
// Boost.Odeint path (odeint_adapter.hpp) against the implicit solver.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <furniture_fem/odeint/odeint_adapter.hpp>
#include <furniture_fem/core/simulation.hpp>

#include "../support/cantilever.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

using namespace furniture_fem;

namespace integrators_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double pi = std::numbers::pi;

// One element clamped at node 0 with only the axial DOF of node 1 free: x'' + omega^2 x = 0 with
// omega^2 = (EA/L) / (rho A L / 2). Axial motion is exactly linear in the corotational kinematics.
struct Oscillator {
  Model model;
  int free_node = 1;
  double omega = 0;
  Oscillator() {
    const int b = model.add_body("bar");
    const int sec = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
    const int mat = model.add_material(Material::steel());
    const int n0 = model.add_node({0, 0, 0}, b);
    free_node = model.add_node({1, 0, 0}, b);
    MemberOptions o;
    o.elements = 1;
    o.pairs = false;
    model.add_member("bar", n0, free_node, sec, mat, o);
    model.fix(n0);
    model.fix(free_node, ALL_DOFS & ~UX);
    omega = std::sqrt(2 * model.materials()[mat].E / model.materials()[mat].rho);  // L = 1
  }
  // x_n for n = 0..steps after starting from x = 0, v = v0.
  template <class Integrator>
  std::vector<double> history(const Integrator& integrator, double dt, int steps, double v0 = 1e-3) const {
    SimulationOptions opt;
    opt.gravity.setZero();
    opt.dt = dt;
    Simulation<ConventionalTimoshenko, Integrator> sim(model, integrator, opt);
    sim.set_velocity(free_node, (Vec6() << v0, 0, 0, 0, 0, 0).finished());
    std::vector<double> x{0.0};
    for (int i = 0; i < steps; ++i) {
      sim.step();
      x.push_back(sim.displacement(free_node).x());
    }
    return x;
  }
};

// Largest root modulus of the recurrence x_{n+1} = c1 x_n + c2 x_{n-1} + c3 x_{n-2} fitted to x by
// least squares: the measured spectral radius of a three-stage one-step map.
double fitted_spectral_radius3(const std::vector<double>& x) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (std::size_t i = 2; i + 1 < x.size(); ++i) {
    const Eigen::Vector3d row(x[i], x[i - 1], x[i - 2]);
    A += row * row.transpose();
    r += row * x[i + 1];
  }
  const Eigen::Vector3d c = A.ldlt().solve(r);
  Eigen::Matrix3d companion;
  companion << c[0], c[1], c[2], 1, 0, 0, 0, 1, 0;
  return companion.eigenvalues().cwiseAbs().maxCoeff();
}

// HHT-alpha in Hilber's own form, an integrator of its own through the stepper API (not AlphaStepper):
//   M a_{n+1} + (1 + alpha) (C v_{n+1} + K u_{n+1}) - alpha (C v_n + K u_n) = (1 + alpha) f_{n+1} - alpha f_n
// with Newmark's update, beta = (1 - alpha)^2 / 4 and gamma = 1/2 - alpha, iterated to equilibrium.
class HilberStepper {
 public:
  HilberStepper(double alpha, double dt)
      : alpha_(alpha), beta_(0.25 * (1 - alpha) * (1 - alpha)), gamma_(0.5 - alpha), dt_(checked_step_length(dt, "HHT")) {}
  double dt() const { return dt_; }
  double stiffness_factor() const { return 1 + alpha_; }
  double velocity_factor() const { return gamma_ / (beta_ * dt_); }
  double mass_factor(double c) const { return 1 / (beta_ * dt_ * dt_) + (1 + alpha_) * velocity_factor() * c; }
  template <class V>
  struct Rates {
    V acceleration, velocity;
  };
  template <class V>
  Rates<V> update(const V& du, const V& vn, const V& an) const {
    const V a = (du - dt_ * vn - dt_ * dt_ * (0.5 - beta_) * an) / (beta_ * dt_ * dt_);
    return {a, vn + dt_ * ((1 - gamma_) * an + gamma_ * a)};
  }
  template <class V>
  V contact_velocity(const V& vn, const V& an) const {
    return vn + dt_ * an;
  }
  template <class V>
  V at_inertia_point(const V& x1, const V&) const {
    return x1;
  }
  template <class V>
  V at_force_point(const V& x1, const V& x0) const {
    return (1 + alpha_) * x1 - alpha_ * x0;
  }
  double end_force_share() const { return gamma_; }
  template <class System>
  StepInfo do_step(System& system) const {
    return IteratedScheme::step(system);
  }

 private:
  double alpha_, beta_, gamma_, dt_;
};
struct Hilber {
  double alpha = -0.1;
  HilberStepper stepper(double dt) const { return {alpha, dt}; }
  std::string name() const { return "HHT-alpha in Hilber's form"; }
};
static_assert(IntegratorPolicy<Hilber>);
static_assert(!IntegratorPolicy<IntegratorCoefficients>);

// The phase per step of a sequence that obeys x_{n+1} + x_{n-1} = 2 cos(phi) x_n (an undamped
// oscillation), fitted by least squares.
double fitted_phase_per_step(const std::vector<double>& x) {
  double num = 0, den = 0;
  for (std::size_t i = 1; i + 1 < x.size(); ++i) {
    num += x[i] * (x[i + 1] + x[i - 1]);
    den += 2 * x[i] * x[i];
  }
  return std::acos(num / den);
}

}  // namespace

TEST_CASE("an integrator of its own (HHT-alpha in Hilber's form) steps the Simulation as its analysis says", "[integrators][stepper]") {
  // A second implementation of HHT-alpha, through the stepper API alone. (1) alpha = 0 is the
  // trapezoidal rule: no decay and the closed-form phase 2 atan(omega dt / 2) per step (the period
  // lengthened by omega dt / (2 atan(omega dt / 2))). Linear problem: the recurrence holds up to
  // rounding (a scalar emulation of it in double precision fits the phase to 4e-16); bound 1e-9 for
  // the element's rounding.
  // (2) alpha < 0: the fitted spectral radius of 200 steps is the one-step map's
  // (spectral_radius() of HhtAlpha's coefficients, an independent analysis), to 1e-7 as for
  // generalized-alpha above; and the steps are the library's HhtAlpha's (generalized-alpha with
  // am = 0, af = -alpha) up to rounding (bound 1e-9 of the amplitude).
  const Oscillator osc;
  for (const double W : {0.3, 1.0, 4.0}) {
    const auto x = osc.history(Hilber{0.0}, W / osc.omega, 200);
    const double phase = fitted_phase_per_step(x), expected = 2 * std::atan(W / 2);
    INFO("omega dt " << W << ": phase per step " << phase << ", closed form " << expected << ", period ratio "
                     << W / expected);
    CHECK(std::abs(phase - expected) < 1e-9);
    CHECK(std::abs(fitted_spectral_radius3(x) - 1) < 1e-6);  // rank-deficient fit (a_n slaved): looser
  }
  for (const double alpha : {-0.05, -0.2, -1.0 / 3.0}) {
    for (const double W : {0.3, 1.0, 4.0}) {
      const double dt = W / osc.omega;
      const auto x = osc.history(Hilber{alpha}, dt, 200);
      const auto library = osc.history(HhtAlpha{alpha}, dt, 200);
      const double measured = fitted_spectral_radius3(x), expected = spectral_radius(HhtAlpha{alpha}.coefficients(), W);
      INFO("alpha " << alpha << ", omega dt " << W << ": measured " << measured << ", expected " << expected);
      CHECK(std::abs(measured - expected) < 1e-7);
      double diff = 0;
      for (std::size_t i = 0; i < x.size(); ++i) diff = std::max(diff, std::abs(x[i] - library[i]));
      CHECK(diff <= 1e-9 * 1e-3 / osc.omega);
    }
  }
  // The closed form at infinity, rho = (1 + alpha) / (1 - alpha), against the analysis.
  for (const double alpha : {-0.05, -0.2, -1.0 / 3.0})
    CHECK(spectral_radius(HhtAlpha{alpha}.coefficients(), 1e6) == Approx((1 + alpha) / (1 - alpha)).margin(1e-4));
}

TEST_CASE("a stepper checks its step length, naming the value", "[integrators][stepper][input]") {
  // One definition (step_length.hpp) for the Simulation, the integrators and the scene's dt.
  CHECK(step_length_problem(1e-3).empty());
  CHECK(step_length_problem(min_step_length).empty());
  CHECK(step_length_problem(0.0) == "must be positive (got 0)");
  CHECK(step_length_problem(-1e-3) == "must be positive (got -0.001)");
  CHECK(step_length_problem(1e-12) == "must be at least 1e-09 s (got 1e-12)");
  CHECK(step_length_problem(5e-7, 1e-6) == "must be at least 1e-06 s (got 5e-07)");
  CHECK(step_length_problem(std::nan("")) == "must be finite (got nan)");
  CHECK(step_length_problem(HUGE_VAL) == "must be finite (got inf)");
  CHECK_THROWS_WITH(Newmark::paper().stepper(1e-300), "integrator: dt must be at least 1e-09 s (got 1e-300)");
  CHECK_THROWS_WITH(GeneralizedAlpha{0.8}.stepper(-2.0), "integrator: dt must be positive (got -2)");
  CHECK_THROWS_AS(Hilber{-0.1}.stepper(0.0), ModelError);
  CHECK(Newmark::paper().stepper(2e-3).dt() == 2e-3);
}

TEST_CASE("generalized-alpha with rho_inf = 1 is the trapezoidal rule", "[integrators]") {
  const auto c = GeneralizedAlpha{1.0}.coefficients();
  CHECK(c.alpha_m == 0.5);
  CHECK(c.alpha_f == 0.5);
  CHECK(c.beta == 0.25);
  CHECK(c.gamma == 0.5);
  // HHT with alpha = 0 is Newmark's average acceleration; both keep |lambda| = 1 at every omega dt.
  const auto h = HhtAlpha{0.0}.coefficients();
  CHECK((h.alpha_m == 0 && h.alpha_f == 0 && h.beta == 0.25 && h.gamma == 0.5));
  for (const double W : {0.1, 1.0, 10.0, 100.0}) {
    CHECK(spectral_radius(c, W) == Approx(1.0).margin(1e-9));
    CHECK(Newmark::average_acceleration().spectral_radius(W) == Approx(1.0).margin(1e-9));
  }
  // The paper's Newmark sits on the optimal-damping line beta = (gamma + 1/2)^2 / 4.
  const auto p = Newmark::paper().coefficients();
  CHECK(p.beta == Approx((p.gamma + 0.5) * (p.gamma + 0.5) / 4).epsilon(1e-15));
}

TEST_CASE("the spectral radius at large omega dt tends to rho_inf", "[integrators]") {
  // The approach is slow where rho_inf = 0 (the limit map is nilpotent: rho ~ W^(-2/3), measured
  // 2.2e-3 at W = 1e4 and 1.0e-4 at W = 1e6; 6.9e-5 for rho_inf = 0.3): at W = 1e6, bound 1e-3.
  for (const double rho_inf : {0.0, 0.3, 0.5, 0.8, 1.0}) {
    const auto c = GeneralizedAlpha{rho_inf}.coefficients();
    INFO("rho_inf = " << rho_inf << ": rho(1e4) = " << spectral_radius(c, 1e4) << ", rho(1e6) = " << spectral_radius(c, 1e6));
    CHECK(std::abs(spectral_radius(c, 1e6) - rho_inf) < 1e-3);
    CHECK(std::abs(spectral_radius(c, 1e4) - rho_inf) < std::abs(spectral_radius(c, 1e2) - rho_inf) + 1e-9);
    // Second-order accurate and unconditionally stable: rho <= 1 everywhere, ~1 at small W.
    for (const double W : {1e-3, 0.1, 1.0, 3.0, 30.0}) CHECK(spectral_radius(c, W) <= 1 + 1e-12);
    CHECK(spectral_radius(c, 1e-3) == Approx(1.0).margin(1e-6));
  }
  CHECK_THROWS_AS(GeneralizedAlpha{1.5}.coefficients(), ModelError);
  CHECK_THROWS_AS(HhtAlpha{-0.5}.coefficients(), ModelError);
  CHECK_THROWS_AS((Newmark{0.25, 0.4}.coefficients()), ModelError);
}

TEST_CASE("the Simulation's generalized-alpha steps decay as spectral_radius() says", "[integrators]") {
  // The oscillator's x_n under a generalized-alpha scheme obey the characteristic cubic of the
  // one-step map on (x, v, a); its root moduli are fitted from 200 steps. Linear problem: the fit
  // reproduces the analysis to ~1e-10; bound 1e-7.
  const Oscillator osc;
  for (const double rho_inf : {0.0, 0.5, 0.9}) {
    for (const double W : {0.3, 1.0, 4.0}) {
      const GeneralizedAlpha ga{rho_inf};
      const auto x = osc.history(ga, W / osc.omega, 200);
      const double measured = fitted_spectral_radius3(x), expected = spectral_radius(ga.coefficients(), W);
      INFO("rho_inf " << rho_inf << ", omega dt " << W << ": measured " << measured << ", expected " << expected);
      CHECK(std::abs(measured - expected) < 1e-7);
    }
  }
}

TEST_CASE("average acceleration is second order, the paper's Newmark first order", "[integrators][order]") {
  // Largest error over two periods against x = sin(omega t) v0/omega, halving dt twice. A scheme of
  // order p divides the error by 2^p: average acceleration (gamma = 1/2) p = 2 (phase error),
  // gamma = 5/6 p = 1 (its numerical damping is O(dt)). Ratios within 10 % of 4 and of 2.
  const Oscillator osc;
  const double T = 2 * (2 * pi / osc.omega), v0 = 1e-3;
  auto error = [&](const Newmark& nm, int steps) {
    const auto x = osc.history(nm, T / steps, steps, v0);
    double e = 0;
    for (int i = 0; i <= steps; ++i)
      e = std::max(e, std::abs(x[i] - v0 / osc.omega * std::sin(osc.omega * T * i / steps)));
    return e / (v0 / osc.omega);
  };
  for (const auto& [nm, order] : {std::pair{Newmark::average_acceleration(), 2}, std::pair{Newmark::paper(), 1}}) {
    const double e1 = error(nm, 200), e2 = error(nm, 400), e3 = error(nm, 800);
    INFO(nm.name() << ": errors " << e1 << ", " << e2 << ", " << e3);
    CHECK(e1 / e2 == Approx(std::pow(2.0, order)).epsilon(0.1));
    CHECK(e2 / e3 == Approx(std::pow(2.0, order)).epsilon(0.1));
  }
}

TEST_CASE("carry-over and iterate give the same steps on a linear problem", "[integrators]") {
  // One solve is exact when the problem is linear, so the two equilibrium modes coincide.
  const Oscillator osc;
  const double dt = 0.5 / osc.omega;
  const auto a = osc.history(Newmark::paper(EquilibriumMode::carry_over), dt, 50);
  const auto b = osc.history(Newmark::paper(EquilibriumMode::iterate), dt, 50);
  for (std::size_t i = 0; i < a.size(); ++i) CHECK(a[i] == Approx(b[i]).margin(1e-12 * 1e-3 / osc.omega));
}

TEST_CASE("Boost.Odeint RK4 through the adapter matches the implicit solver", "[integrators][odeint]") {
  // A 1 m cantilever (8 ASI-Gauss elements, no gravity) released with an initial velocity in the
  // shape of its static deflection (tip 5 m/s: amplitude 15 mm, 1.5 % of L, so mildly nonlinear), two
  // periods of free vibration. Reference: average-acceleration Newmark iterated to equilibrium,
  // dt = 20 us (period error (omega dt)^2/12 < 1e-4 for the first mode). Explicit: classical RK4 at
  // half its stability limit 2.83/omega_max. The tip histories agree within 1 % of the amplitude
  // (measured 1.3e-4).
  const ffem_test::Cantilever c;
  const Model& m = c.model;
  const int tip = c.tip;
  SimulationOptions opt;
  opt.gravity.setZero();
  opt.dt = 2e-5;
  using Sim = Simulation<AsiGaussTimoshenko>;
  auto release = [&](Sim& sim) { c.release_in_static_shape(sim, 5.0); };
  const double T = 0.04;

  Sim implicit(m, Newmark::average_acceleration(EquilibriumMode::iterate), opt);
  release(implicit);
  std::vector<double> y_implicit;
  implicit.run_until(T, [&](const Sim& s, const StepInfo&) { y_implicit.push_back(s.displacement(tip).y()); });

  Sim model_for_odeint(m, Newmark{}, opt);
  release(model_for_odeint);
  OdeintSystem<Sim> system(model_for_odeint);
  const double wmax = system.max_frequency();
  const int sub = static_cast<int>(std::ceil(opt.dt / (0.5 * 2.83 / wmax)));  // RK4 steps per implicit step
  const double dt_explicit = opt.dt / sub;
  std::vector<double> y_explicit;
  double y_last = 0;
  long calls = 0;
  const std::size_t steps = integrate_explicit(
      boost::numeric::odeint::runge_kutta4<std::vector<double>>(), system, 0.0, T + 0.5 * opt.dt, dt_explicit,
      [&](const std::vector<double>& x, double) {
        y_last = system.displacement(x, tip).y();
        if (calls++ % sub == 0 && calls > 1) y_explicit.push_back(y_last);
      });
  REQUIRE(steps >= static_cast<std::size_t>(sub) * y_implicit.size());
  REQUIRE(y_explicit.size() >= y_implicit.size());

  double amplitude = 0, diff = 0;
  for (std::size_t i = 0; i < y_implicit.size(); ++i) {
    amplitude = std::max(amplitude, std::abs(y_implicit[i]));
    diff = std::max(diff, std::abs(y_implicit[i] - y_explicit[i]));
  }
  INFO("omega_max " << wmax << " rad/s, RK4 dt " << dt_explicit << " s, amplitude " << amplitude
                    << " m, max difference " << diff << " m (" << diff / amplitude << " of the amplitude)");
  CHECK(amplitude > 0.01);
  CHECK(diff < 0.01 * amplitude);
  // The final state was written back into the Simulation.
  CHECK(model_for_odeint.displacement(tip).y() == y_last);
}

TEST_CASE("the odeint system holds the fixed DOFs and integrates free fall exactly", "[integrators][odeint]") {
  // Gravity only on a free bar: RK4 integrates a constant acceleration exactly (bound: round-off).
  Model m;
  const int b = m.add_body("bar");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = m.add_material(Material::steel());
  const int n0 = m.add_node({0, 0, 0}, b), n1 = m.add_node({0.5, 0, 0}, b);
  MemberOptions o;
  o.elements = 2;
  m.add_member("bar", n0, n1, sec, mat, o);
  m.fix(n0, UX);  // one DOF held: it must not move, and this restraint produces no force on a free fall
  Simulation<AsiGaussTimoshenko> sim(m);
  OdeintSystem<Simulation<AsiGaussTimoshenko>> system(sim);
  integrate_explicit(boost::numeric::odeint::runge_kutta4<std::vector<double>>(), system, 0.0, 0.1, 1e-5);
  const double g = 9.80665;
  for (int n = 0; n < m.num_nodes(); ++n) {
    CHECK(sim.displacement(n).z() == Approx(-0.5 * g * 0.01).epsilon(1e-9));
    CHECK(sim.displacement(n).x() == Approx(0).margin(1e-12));
  }
  CHECK(sim.velocity(n1)[2] == Approx(-g * 0.1).epsilon(1e-9));
}

TEST_CASE("the odeint system refuses structural damping, naming it", "[integrators][odeint][input]") {
  // stiffness_damping is a rate over the implicit step's deformation increment; the explicit system has
  // no step to take it over, so it says so instead of running undamped.
  Model m;
  const int b = m.add_body("bar");
  const int n1 = m.add_node({0, 0, 0}, b), n2 = m.add_node({1, 0, 0}, b);
  MemberOptions o;
  o.elements = 2;
  m.add_member("bar", n1, n2, m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002)), m.add_material(Material::steel()), o);
  SimulationOptions opt;
  opt.stiffness_damping = 1e-4;
  Simulation<AsiGaussTimoshenko> sim(m, Newmark::paper(), opt);
  REQUIRE_THROWS_WITH(OdeintSystem<Simulation<AsiGaussTimoshenko>>(sim),
                      Catch::Contains("stiffness_damping is not supported") && Catch::Contains("(got 0.0001 s)"));
  opt.stiffness_damping = 0;
  Simulation<AsiGaussTimoshenko> undamped(m, Newmark::paper(), opt);
  CHECK_NOTHROW(OdeintSystem<Simulation<AsiGaussTimoshenko>>(undamped));
}

}  // namespace integrators_tests
