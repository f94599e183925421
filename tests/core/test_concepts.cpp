// The minimal policy implementations of docs/core/concept_element.md, docs/core/concept_integrator.md and
// docs/core/concept_linear_solver.md, verbatim, each composed into a Simulation and checked on a result.
// If this file stops compiling, the documents are out of date.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <furniture_fem/core/simulation.hpp>

#include "../support/cantilever.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

using namespace furniture_fem;

namespace concepts_tests {  // this file's own names (its group compiles files in batches)

// ---- docs/core/concept_element.md: a minimal Element policy ------------------------------------------
// The elastic linear Timoshenko beam with its single integration point at the centre (s = 0). It works
// in the element's corotated frame: d holds the local deformations [u1 v1 w1 tx1 ty1 tz1 u2 ... tz2]
// (the frame follows the chord, so v and w are zero and the rotations are relative to the chord).
struct ElasticCentreTimoshenko {
  static constexpr std::string_view name = "elastic one-point Timoshenko";
  static constexpr bool needs_pairs = false;  // any element count, no ASI-Gauss pairs
  struct State {};                            // no history: nothing to commit

  static State initial_state(const ElementProps&) { return {}; }

  // Generalised strains (eps, gamma_xy, gamma_xz, kappa_x, kappa_y, kappa_z) at the centre.
  static Eigen::Matrix<double, 6, 12> B(double L) {
    Eigen::Matrix<double, 6, 12> b = Eigen::Matrix<double, 6, 12>::Zero();
    b(0, 0) = -1 / L, b(0, 6) = 1 / L;                                     // u'
    b(1, 1) = -1 / L, b(1, 7) = 1 / L, b(1, 5) = -0.5, b(1, 11) = -0.5;    // v' - theta_z
    b(2, 2) = -1 / L, b(2, 8) = 1 / L, b(2, 4) = 0.5, b(2, 10) = 0.5;      // w' + theta_y
    b(3, 3) = -1 / L, b(3, 9) = 1 / L;                                     // theta_x'
    b(4, 4) = -1 / L, b(4, 10) = 1 / L;                                    // theta_y'
    b(5, 5) = -1 / L, b(5, 11) = 1 / L;                                    // theta_z'
    return b;
  }
  // Local forces f, tangent k and trial history from the committed history and the deformations.
  static void response(const ElementProps& p, const State&, const Vec12& d, Vec12& f, Mat12& k, State& trial) {
    const Eigen::Matrix<double, 6, 12> b = B(p.L0);
    const Vec6 D = Eigen::Map<const Vec6>(p.D.data());  // EA, kGA_y, kGA_z, GJ, EI_y, EI_z
    k = p.L0 * b.transpose() * D.asDiagonal() * b;      // one-point rule: weight 2 x Jacobian L/2
    f = k * d;
    trial = {};
  }
  // Sectional forces (N, Qy, Qz, Mx, My, Mz) and where they act (xi = 0: the centre).
  static SectionForces section_forces(const ElementProps& p, const State&, const Vec12& d) {
    const Vec6 s = Eigen::Map<const Vec6>(p.D.data()).cwiseProduct(B(p.L0) * d);
    return {s[0], s[1], s[2], s[3], s[4], s[5], 0.0};
  }
};
static_assert(ElementPolicy<ElasticCentreTimoshenko>);

// ---- docs/core/concept_integrator.md: a minimal Integrator policy ------------------------------------
// Wood-Bossak-Zienkiewicz alpha (alpha_f = 0, alpha_m = alpha in [-1/3, 0]): second order,
// unconditionally stable, spectral radius at infinity (1 + alpha) / (1 - alpha).
struct BossakAlpha {
  double alpha = -0.1;
  EquilibriumMode mode = EquilibriumMode::iterate;
  IntegratorCoefficients coefficients() const {
    return {alpha, 0.0, 0.25 * (1 - alpha) * (1 - alpha), 0.5 - alpha};  // alpha_m, alpha_f, beta, gamma
  }
  AlphaStepper stepper(double dt) const { return {coefficients(), mode, dt}; }  // the family's stepper
  std::string name() const { return "Bossak alpha " + std::to_string(alpha); }
};
static_assert(IntegratorPolicy<BossakAlpha>);

// ---- docs/core/concept_linear_solver.md: a minimal LinearSolver policy --------------------------------
// Dense LDL^T of the body's effective matrix: fine for a few hundred DOFs, a reference for others.
class DenseLdltSolver {
 public:
  static constexpr std::string_view name = "dense LDL^T";
  void analyse(const SparseMatrix&) {}  // nothing to do per sparsity pattern
  void factorize(const SparseMatrix& K) { ldlt_.compute(Eigen::MatrixXd(K)); }
  bool solve(const Eigen::VectorXd& r, Eigen::VectorXd& x) {
    x = ldlt_.solve(r);
    return ldlt_.info() == Eigen::Success && x.allFinite();
  }

 private:
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};
static_assert(LinearSolverPolicy<DenseLdltSolver>);

// ---- the checks -----------------------------------------------------------------------------------
namespace {

using ffem_test::Cantilever;

SimulationOptions no_gravity() {
  SimulationOptions o;
  o.gravity.setZero();
  return o;
}

}  // namespace

TEST_CASE("a user Element policy composes into a Simulation", "[concepts][element]") {
  // Four one-point elements under a tip load: (1 - 1/(4 n^2)) of the bending deflection plus the
  // exact shear deflection, and the same numbers as the library's ConventionalTimoshenko.
  const Cantilever c({.elements = 4, .pairs = false, .yield_stress = 1e20});
  const double P = 0.01;
  Simulation<ElasticCentreTimoshenko> sim(c.model, Newmark{}, no_gravity());
  sim.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
  REQUIRE(sim.solve_static(1, 50, 1e-12).converged);
  const double v = sim.displacement(c.tip).y();
  const double expected = P * ((1 - 1.0 / 64) / (3 * c.EI()) + 1 / c.GAs());
  CHECK(v == Approx(expected).epsilon(1e-9));

  Simulation<ConventionalTimoshenko> lib(c.model, Newmark{}, no_gravity());
  lib.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
  REQUIRE(lib.solve_static(1, 50, 1e-12).converged);
  CHECK(v == Approx(lib.displacement(c.tip).y()).epsilon(1e-12));
  // Sectional forces: the root element carries the shear P and the moment P (L - x) at its centre.
  const SectionForces s = sim.section_forces(0);
  CHECK(std::abs(s.Qy) == Approx(P).epsilon(1e-6));
  CHECK(std::abs(s.Mz) == Approx(P * (1 - 0.125)).epsilon(1e-6));
}

TEST_CASE("a user Integrator policy composes into a Simulation", "[concepts][integrator]") {
  // Spectral radius at infinity (1 + alpha)/(1 - alpha); a free vibration of an axial two-DOF chain in
  // its lowest mode at omega dt = 0.05 keeps its amplitude and phase over one period (period error
  // O((omega dt)^2): measured 3e-4 of the amplitude and 1.7e-3 in x(T); bounds 0.5 % and 1 %).
  const BossakAlpha bossak{-0.1};
  CHECK(spectral_radius(bossak.coefficients(), 1e4) == Approx(0.9 / 1.1).margin(2e-3));

  Model m;
  const int b = m.add_body("bar");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = m.add_material(Material::steel());
  const int n0 = m.add_node({0, 0, 0}, b), n1 = m.add_node({1, 0, 0}, b);
  MemberOptions o;
  o.elements = 2;
  m.add_member("bar", n0, n1, sec, mat, o);
  m.fix(n0);
  for (int n = 1; n < m.num_nodes(); ++n) m.fix(n, ALL_DOFS & ~UX);
  SimulationOptions opt = no_gravity();
  // Two axial elements, masses m/4 (middle: m/2) at the nodes: the lowest mode of the 2-DOF chain.
  const double k = 2 * m.materials()[mat].E * m.sections()[sec].A, mu = 7850 * m.sections()[sec].A;
  // K = k [[2, -1], [-1, 1]], M = mu [[1/2, 0], [0, 1/4]]: omega^2 = (k/mu) (4 - 2 sqrt 2)
  const double omega = std::sqrt(k / mu * (4 - 2 * std::sqrt(2.0)));
  opt.dt = 0.05 / omega;
  Simulation<ConventionalTimoshenko, BossakAlpha> sim(m, bossak, opt);
  // Start in the lowest mode, shape (1/sqrt 2, 1) for (middle, end). Node 1 is the end, node 2 the
  // middle node that add_member created.
  const double v0 = 1e-3;
  REQUIRE(sim.nodal_mass(1) == Approx(mu / 4).epsilon(1e-12));
  sim.set_velocity(1, (Vec6() << v0, 0, 0, 0, 0, 0).finished());
  sim.set_velocity(2, (Vec6() << v0 / std::sqrt(2.0), 0, 0, 0, 0, 0).finished());
  double amplitude = 0;
  const double T = 2 * std::numbers::pi / omega;
  sim.run_until(T, [&](const auto& s, const StepInfo&) { amplitude = std::max(amplitude, s.displacement(1).x()); });
  // After one period (the step nearest T): the exact x = (v0/omega) sin(omega t) at that time.
  const double x_exact = v0 / omega * std::sin(omega * sim.time());
  INFO("amplitude " << amplitude << ", expected " << v0 / omega << "; x(t = " << sim.time() << ") "
                    << sim.displacement(1).x() << ", exact " << x_exact);
  CHECK(amplitude == Approx(v0 / omega).epsilon(5e-3));
  CHECK(std::abs(sim.displacement(1).x() - x_exact) < 0.01 * v0 / omega);
}

TEST_CASE("a user LinearSolver policy composes into a Simulation", "[concepts][solver]") {
  // The dense solver reproduces the sparse direct solver on a nonlinear static solve (tip load
  // P L^2/(EI) = 2) and on dynamic steps.
  const Cantilever c({.elements = 10, .pairs = true, .yield_stress = 1e20});
  const double P = 2 * c.EI();
  Simulation<AsiGaussTimoshenko, Newmark, DenseLdltSolver> dense(c.model, Newmark{}, no_gravity());
  Simulation<AsiGaussTimoshenko> sparse(c.model, Newmark{}, no_gravity());
  dense.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
  sparse.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
  REQUIRE(dense.solve_static(5, 50, 1e-11).converged);
  REQUIRE(sparse.solve_static(5, 50, 1e-11).converged);
  CHECK((dense.position(c.tip) - sparse.position(c.tip)).norm() < 1e-9);
  CHECK(dense.position(c.tip).y() == Approx(0.49346).epsilon(0.01));  // the elastica at alpha = 2

  SimulationOptions opt;  // with gravity: free vibration about the deflected shape
  opt.dt = 1e-3;
  Simulation<AsiGaussTimoshenko, Newmark, DenseLdltSolver> d2(c.model, Newmark::paper(), opt);
  Simulation<AsiGaussTimoshenko> s2(c.model, Newmark::paper(), opt);
  for (int i = 0; i < 50; ++i) {
    d2.step();
    s2.step();
  }
  CHECK((d2.displacement(c.tip) - s2.displacement(c.tip)).norm() < 1e-9 * s2.displacement(c.tip).norm());
}

}  // namespace concepts_tests
