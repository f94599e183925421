// Structural damping (SimulationOptions::stiffness_damping, c): each element's deformational force gains
// c k_e (d - d_n) / dt, so a mode at omega is damped at the ratio c omega / 2 and rigid motion is not
// damped. Checked against that closed form on a one-DOF bar and a cantilever's first mode, against an
// undamped run for a free frame's rigid motion, and against the energy ledger.
#include <catch2/catch.hpp>

#include <furniture_fem/core/simulation.hpp>

#include "../support/cantilever.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>
#include <vector>

using namespace furniture_fem;

namespace structural_damping_tests {  // this file's own names (its group compiles files in batches)

namespace {

// The damping ratio of a decaying oscillation from its positive peaks (parabolic interpolation), by the
// logarithmic decrement between the first peak at or after `from` and the last; also the mean period
// (in samples) between those peaks.
struct Decay {
  double zeta = 0, period = 0;
  int cycles = 0;
};
Decay decay_of(const std::vector<double>& x, std::size_t from) {
  std::vector<double> peak, at;
  for (std::size_t i = std::max<std::size_t>(from, 1); i + 1 < x.size(); ++i)
    if (x[i] > x[i - 1] && x[i] >= x[i + 1] && x[i] > 0) {
      const double y0 = x[i - 1], y1 = x[i], y2 = x[i + 1], d = 0.5 * (y0 - y2) / (y0 - 2 * y1 + y2);
      peak.push_back(y1 - 0.25 * (y0 - y2) * d);
      at.push_back(static_cast<double>(i) + d);
    }
  Decay r;
  if (peak.size() < 2) return r;
  r.cycles = static_cast<int>(peak.size()) - 1;
  const double delta = std::log(peak.front() / peak.back()) / r.cycles;
  r.zeta = delta / std::sqrt(4 * std::numbers::pi * std::numbers::pi + delta * delta);
  r.period = (at.back() - at.front()) / r.cycles;
  return r;
}

// One element clamped at node n1, node n2 free only axially: a one-DOF oscillator with k = EA/L and
// m = rho A L / 2 (the lumped node mass), L = 1 m.
struct AxialBar {
  Model m;
  int n1 = 0, n2 = 0;
  double omega = 0;
  AxialBar() {
    const int b = m.add_body("bar");
    const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
    const int mat = m.add_material(Material::steel());
    n1 = m.add_node({0, 0, 0}, b);
    n2 = m.add_node({1, 0, 0}, b);
    MemberOptions o;
    o.elements = 1;
    o.pairs = false;
    m.add_member("bar", n1, n2, sec, mat, o);
    m.fix(n1);
    m.fix(n2, ALL_DOFS & ~UX);
    omega = std::sqrt(m.materials()[mat].E / (m.materials()[mat].rho / 2));
  }
};

}  // namespace

TEST_CASE("structural damping decays a one-DOF bar at the ratio c omega / 2", "[dynamics][damping]") {
  // One element clamped at node 1, node 2 free only axially (k = EA/L, m = rho A L / 2), average
  // acceleration (no numerical damping), omega dt = 0.05, six periods. An independent integration of the
  // same discrete scheme (m a1 + c k (x1 - x0) / dt + k x1 = 0 under Newmark's average acceleration,
  // Python, peaks by the same interpolation) gives the ratio within 0.15 % of c omega / 2 for zeta 0.02 to
  // 0.1 (the backward difference's own error is O(omega dt)^2); measured here 0.01999, 0.05001, 0.1001;
  // bound 0.5 %. Without damping the decrement vanishes (measured -3e-9; bound 1e-6).
  for (const double zeta : {0.0, 0.02, 0.05, 0.1}) {
    const AxialBar bar;
    const double omega = bar.omega;
    SimulationOptions opt;
    opt.gravity.setZero();
    opt.dt = 0.05 / omega;
    opt.stiffness_damping = 2 * zeta / omega;
    Simulation<ConventionalTimoshenko> sim(bar.m, Newmark::average_acceleration(), opt);
    sim.set_velocity(bar.n2, (Vec6() << 1e-3 * omega, 0, 0, 0, 0, 0).finished());
    std::vector<double> x{0.0};
    for (int i = 0; i < static_cast<int>(6 * 2 * std::numbers::pi / 0.05); ++i) {
      sim.step();
      x.push_back(sim.displacement(bar.n2).x());
    }
    const Decay d = decay_of(x, 0);
    INFO("zeta " << zeta << ": measured " << d.zeta << " over " << d.cycles << " cycles");
    REQUIRE(d.cycles >= 5);
    if (zeta == 0) CHECK(std::abs(d.zeta) < 1e-6);
    else CHECK(std::abs(d.zeta / zeta - 1) < 0.005);
  }
}

TEST_CASE("structural damping decays a cantilever's first mode at c omega_1 / 2 and the ledger holds it",
          "[dynamics][damping][energy]") {
  // A 1 m steel cantilever of 8 ASI-Gauss elements (50 x 30 tube), no gravity, set moving in the shape
  // of its static deflection (tip 0.3 m/s), average acceleration iterated to equilibrium, dt 0.1 ms.
  // c is chosen for 3 % and 8 % at the first mode's frequency measured in an undamped run (51.7 Hz); the
  // second mode (6.3 times higher) is damped 6.3 times more, so the peaks after the first period follow
  // the first mode. Measured 0.03002 and 0.08013 over 11 cycles; bound 2 %. The energy the members'
  // dashpots take is the ledger's damping work (99.2 and 99.9998 % of the initial energy): its
  // imbalance measured 1.6e-9 of the initial energy (the iteration's tolerance); bound 1e-6.
  const auto run = [](double c, std::vector<double>& tip, EnergyLedger& ledger) {
    const ffem_test::Cantilever cantilever;
    const Model& m = cantilever.model;
    const int end = cantilever.tip;
    SimulationOptions opt;
    opt.gravity.setZero();
    opt.dt = 1e-4;
    opt.stiffness_damping = c;
    Simulation<AsiGaussTimoshenko> sim(m, Newmark::average_acceleration(EquilibriumMode::iterate), opt);
    cantilever.release_in_static_shape(sim, 0.3);
    tip.assign(1, 0.0);
    sim.run_until(0.25, [&](const auto& s, const StepInfo&) { tip.push_back(s.displacement(end).y()); });
    ledger = sim.energy();
  };
  std::vector<double> tip;
  EnergyLedger ledger;
  run(0.0, tip, ledger);
  const Decay undamped = decay_of(tip, 0);
  const double omega1 = 2 * std::numbers::pi / (undamped.period * 1e-4);
  INFO("first mode " << omega1 / (2 * std::numbers::pi) << " Hz");
  REQUIRE(undamped.cycles >= 6);
  CHECK(std::abs(undamped.zeta) < 1e-3);
  CHECK(ledger.damping_work == 0);
  for (const double zeta : {0.03, 0.08}) {
    run(2 * zeta / omega1, tip, ledger);
    const Decay d = decay_of(tip, static_cast<std::size_t>(undamped.period));
    const double E0 = ledger.initial_total;
    INFO("zeta " << zeta << ": measured " << d.zeta << " over " << d.cycles << " cycles; energy left "
                 << ledger.total() / E0 << ", damping work " << ledger.damping_work / E0 << ", imbalance "
                 << ledger.imbalance() / E0);
    REQUIRE(d.cycles >= 3);
    CHECK(std::abs(d.zeta / zeta - 1) < 0.02);
    CHECK(ledger.damping_work < -0.5 * E0);  // most of the energy went into the dashpots
    CHECK(std::abs(ledger.imbalance()) < 1e-6 * E0);
  }
}

TEST_CASE("structural damping leaves a free frame's rigid motion alone", "[dynamics][damping][conservation]") {
  // The spinning L-frame of test_dynamics.cpp (about a turn a second) with c = 1 ms, a damping ratio of
  // 0.6 to 10 at its flexural modes: the dashpots act on the corotated deformations only, so the linear
  // momentum stays to round-off and the kinetic energy as without damping (the spin's small centrifugal
  // stretch is all they can take: measured 8.9e-6 of the energy, the kinetic energy 1.9e-5 below the
  // undamped run's; bounds 1e-4).
  const auto run = [](double c) {
    Model model;
    const int body = model.add_body("L frame");
    const int sec = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
    const int mat = model.add_material(Material::steel());
    const int a = model.add_node({0, 0, 0}, body), mid = model.add_node({0.6, 0, 0}, body);
    const int d = model.add_node({0.6, 0.4, 0.2}, body);
    MemberOptions o;
    o.elements = 6;
    model.add_member("arm", a, mid, sec, mat, o);
    model.add_member("leg", mid, d, sec, mat, o);
    SimulationOptions opt;
    opt.dt = 1e-3;
    opt.gravity.setZero();
    opt.stiffness_damping = c;
    Simulation<AsiGaussTimoshenko> sim(model, Newmark::average_acceleration(EquilibriumMode::iterate), opt);
    const Vec3 c0 = model.body_centre_of_gravity(body);
    sim.set_body_velocity(body, Vec3(0.3, -0.2, 0.1), Vec3(2, -3, 5), c0);
    const Vec3 p0 = sim.linear_momentum();
    const double E0 = sim.energy().total();
    sim.run_until(2.0);
    return std::tuple{(sim.linear_momentum() - p0).norm() / p0.norm(), sim.energy().kinetic / E0,
                      -sim.energy().damping_work / E0};
  };
  const auto [dp0, k0, w0] = run(0.0);
  const auto [dp, k, w] = run(1e-3);
  INFO("kinetic energy left: " << k << " damped, " << k0 << " undamped; damping work " << w);
  CHECK(dp < 1e-12);
  CHECK(w0 == 0);
  CHECK(w < 1e-4);
  CHECK(std::abs(k - k0) < 1e-4);
}

TEST_CASE("stiffness_damping: a negative or non-finite value is refused, naming it",
          "[dynamics][damping][input]") {
  const AxialBar bar;
  SimulationOptions opt;
  for (const double c : {-1e-4, std::nan(""), std::numeric_limits<double>::infinity()}) {
    opt.stiffness_damping = c;
    INFO("c = " << c);
    REQUIRE_THROWS_WITH((Simulation<ConventionalTimoshenko>(bar.m, Newmark::paper(), opt)),
                        Catch::Contains("stiffness_damping must be finite and at least 0 s (got " + detail::fmt(c) + ")"));
  }
}

}  // namespace structural_damping_tests
