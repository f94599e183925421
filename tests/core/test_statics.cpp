// Statics against closed forms: linear cantilevers (ASI-Gauss exactness, the one-point element's
// 1 - 1/(4 n^2)), large rotations (end moment rolling a beam into a circle), the elastica under a
// fixed-direction tip load (tables and an independent shooting solution), plastic collapse loads.
#include <catch2/catch.hpp>

#include <boost/numeric/odeint/integrate/integrate_const.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <furniture_fem/core/simulation.hpp>

#include "../support/cantilever.hpp"

#include <vector>
#include <cmath>
#include <numbers>

using namespace furniture_fem;

namespace statics_tests {  // this file's own names (its group compiles files in batches)

namespace {

constexpr double pi = std::numbers::pi;

using ffem_test::Cantilever;

SimulationOptions no_gravity() {
  SimulationOptions o;
  o.gravity.setZero();
  return o;
}

template <class Element>
double tip_deflection(const Cantilever& c, double P) {
  Simulation<Element> sim(c.model, Newmark{}, no_gravity());
  sim.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
  const auto res = sim.solve_static(1, 50, 1e-12);
  REQUIRE(res.converged);
  return sim.displacement(c.tip).y();
}

// Angle of a rotation matrix about +Z when it is a rotation about Z (atan2 keeps the full turn's sign).
double angle_about_z(const Mat3& R) { return std::atan2(R(1, 0), R(0, 0)); }

}  // namespace

TEST_CASE("one ASI-Gauss pair gives the exact cantilever tip deflection", "[statics][asi-gauss]") {
  // P L^3 / (3 E I) + P L / (k G A): the pair's stress points sit on the two Gauss points of the pair,
  // which integrates the linear moment and the constant shear of a tip-loaded cantilever exactly.
  // A 0.01 N load keeps the geometric nonlinearity (of relative size (v/L)^2 ~ 1e-14) below round-off,
  // so 1e-9 is a round-off bound (the Newton solve stops at a relative residual of 1e-12).
  for (int n : {2, 4, 8}) {
    const Cantilever c({.length = 1.0, .elements = n, .pairs = true});
    const double P = 0.01;
    const double exact = P * (c.bending_flexibility() + c.shear_flexibility());
    const double v = tip_deflection<AsiGaussTimoshenko>(c, P);
    INFO("elements " << n << ", v = " << v << ", exact = " << exact);
    CHECK(std::abs(v / exact - 1) < 1e-9);
  }
}

TEST_CASE("the one-point element gives 1 - 1/(4 n^2) of the bending deflection", "[statics][one-point]") {
  // n one-point (s = 0) Timoshenko elements: the bending part of the tip deflection is
  // (1 - 1/(4 n^2)) P L^3/(3 E I) and the shear part P L/(k G A) is exact. The 1e-6 bound is loose
  // against round-off; it would catch any change of the element's integration point.
  for (int n : {2, 4, 8}) {
    const Cantilever c({.length = 1.0, .elements = n, .pairs = false});
    const double P = 0.01;
    const double expected = P * ((1 - 1.0 / (4.0 * n * n)) * c.bending_flexibility() + c.shear_flexibility());
    const double v = tip_deflection<ConventionalTimoshenko>(c, P);
    INFO("elements " << n << ", v = " << v << ", expected = " << expected);
    CHECK(std::abs(v / expected - 1) < 1e-6);
  }
}

TEST_CASE("an end moment 2 pi EI / L rolls a cantilever into a full circle", "[statics][large-rotation]") {
  // Pure bending: the beam bends into a circular arc of radius EI/M. With kappa = M/EI the tip is at
  // (sin(kappa L)/kappa, (1 - cos(kappa L))/kappa) and has turned by kappa L. 40 elements, the load
  // in about one increment per 9 degrees of tip rotation; a 1 % of L bound as specified (the measured
  // errors are near 1e-4 L, from the chord approximation of the arc).
  for (const double turn : {0.25, 0.5, 1.0}) {
    Cantilever c({.length = 1.0, .elements = 40, .pairs = true, .yield_stress = 1e20});  // elastic: yield far away
    Simulation<AsiGaussTimoshenko> sim(c.model, Newmark{}, no_gravity());
    const double kappa = 2 * pi * turn / c.L, M = kappa * c.EI();
    sim.set_nodal_load(c.tip, (Vec6() << 0, 0, 0, 0, 0, M).finished());
    const auto res = sim.solve_static(static_cast<int>(40 * turn) + 2, 60, 1e-10);
    REQUIRE(res.converged);
    const Vec3 x = sim.position(c.tip);
    const double xe = std::sin(kappa * c.L) / kappa, ye = (1 - std::cos(kappa * c.L)) / kappa;
    INFO("M L/EI = " << kappa * c.L << ": tip (" << x.x() << ", " << x.y() << "), exact (" << xe << ", " << ye
                     << "), error / L = " << std::hypot(x.x() - xe, x.y() - ye) / c.L);
    CHECK(std::hypot(x.x() - xe, x.y() - ye) < 0.01 * c.L);
    CHECK(std::abs(x.z()) < 1e-9 * c.L);
    // Tip rotation kappa L about Z (compared on the circle, so that 2 pi reads as 0).
    const double a = angle_about_z(sim.rotation(c.tip)), ae = kappa * c.L;
    CHECK(std::abs(std::remainder(a - ae, 2 * pi)) < 0.01 * ae);
    if (turn == 1.0) CHECK(x.norm() < 0.01 * c.L);  // the tip is back at the root
  }
}

namespace {

// The elastica of a cantilever under a fixed-direction tip load P normal to its initial axis:
// with s the arc length over L, theta the slope and alpha = P L^2 / (E I),
//     theta'' = -alpha cos(theta),  x' = cos(theta),  y' = sin(theta),
//     theta(0) = 0, x(0) = y(0) = 0, theta'(1) = 0 (no moment at the free end).
// Shooting on theta'(0) in [0, alpha] (theta'(1) is negative at 0 and non-negative at alpha) by
// bisection, each shot integrated by odeint's classical Runge-Kutta with 2000 steps (error ~1e-12).
struct Elastica {
  double v_over_L = 0, shortening_over_L = 0;
};
Elastica shoot_elastica(double alpha) {
  using state = std::vector<double>;  // theta, theta', x, y
  namespace odeint = boost::numeric::odeint;
  auto shot = [alpha](double k0) {
    state z{0.0, k0, 0.0, 0.0};  // (a std::array state makes GCC 12 warn inside odeint's array algebra)
    auto rhs = [alpha](const state& q, state& dq, double) {
      dq[0] = q[1];
      dq[1] = -alpha * std::cos(q[0]);
      dq[2] = std::cos(q[0]);
      dq[3] = std::sin(q[0]);
    };
    odeint::runge_kutta4<state> stepper;
    odeint::integrate_const(stepper, rhs, z, 0.0, 1.0, 1.0 / 2000);
    return z;
  };
  double lo = 0, hi = alpha;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (shot(mid)[1] < 0 ? lo : hi) = mid;
  }
  const state z = shot(0.5 * (lo + hi));
  return {z[3], 1 - z[2]};
}

}  // namespace

TEST_CASE("a cantilever under a large fixed-direction tip load follows the elastica", "[statics][elastica]") {
  // Reference: Mattiasson (1981) / Bisshopp & Drucker (1945), tip deflection v/L and (L - x_tip)/L at
  // P L^2/(E I) = 1, 2, 5, 10; and the shooting solution above. The FE model (2 m, 40 ASI-Gauss
  // elements, elastic) includes shear and axial strain, which the elastica ignores: both are below
  // 0.1 % here (3 EI/(kGA L^2) = 1e-3), so 1 % of each value bounds the comparison with margin.
  struct Row {
    double alpha, v, shortening;
  };
  const Row table[] = {{1, 0.30172, 0.05643}, {2, 0.49346, 0.16064}, {5, 0.71379, 0.38763}, {10, 0.81061, 0.55500}};
  for (const auto& r : table) {
    const Elastica e = shoot_elastica(r.alpha);
    INFO("alpha = " << r.alpha << ": shooting v/L = " << e.v_over_L << ", (L - x)/L = " << e.shortening_over_L);
    // The shooting solution reproduces the tables to their 5 digits.
    CHECK(e.v_over_L == Approx(r.v).margin(1e-5));
    CHECK(e.shortening_over_L == Approx(r.shortening).margin(1e-5));

    Cantilever c({.length = 2.0, .elements = 40, .pairs = true, .yield_stress = 1e20});
    Simulation<AsiGaussTimoshenko> sim(c.model, Newmark{}, no_gravity());
    const double P = r.alpha * c.EI() / (c.L * c.L);
    sim.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
    const auto res = sim.solve_static(static_cast<int>(2 * r.alpha) + 2, 60, 1e-10);
    REQUIRE(res.converged);
    const Vec3 x = sim.position(c.tip);
    const double v = x.y() / c.L, shortening = (c.L - x.x()) / c.L;
    INFO("FE v/L = " << v << ", (L - x)/L = " << shortening);
    CHECK(std::abs(v / e.v_over_L - 1) < 0.01);
    CHECK(std::abs(shortening / e.shortening_over_L - 1) < 0.01);
    CHECK(std::abs(v / r.v - 1) < 0.01);
    CHECK(std::abs(shortening / r.shortening - 1) < 0.01);
  }
}

TEST_CASE("cantilever pushed by displacement control collapses at Mp / L", "[statics][plastic]") {
  // Displacement control: a support spring 1000 times stiffer than the cantilever pulls the tip
  // towards a target (scaled by the load factor); its force is the tip load. Elastic stiffness
  // k_el = 1/(L^3/(3EI) + L/(kGA)); collapse when the root moment P x_tip reaches Mp = sigma_y Zpz,
  // so P = Mp / L up to the tip's shortening (0.2 % at 2.5 times the yield displacement) and the
  // yield surface drift: 2 % as specified.
  Cantilever c({.length = 1.0, .elements = 10, .pairs = true});
  const double kel = 1.0 / (c.bending_flexibility() + c.shear_flexibility());
  const double Pc = c.Mp() / c.L, dy = Pc / kel;

  SECTION("elastic below the yield displacement") {
    Simulation<AsiGaussTimoshenko> sim(c.model, Newmark{}, no_gravity());
    const int sp = sim.add_support_spring(c.tip, 1, 1e3 * kel, 0.5 * dy);
    REQUIRE(sim.solve_static(10, 50, 1e-10).converged);
    const double slope = sim.spring_force(sp) / sim.displacement(c.tip).y();
    INFO("elastic slope / k_el = " << slope / kel);
    CHECK(std::abs(slope / kel - 1) < 2e-3);  // geometric nonlinearity at v/L = 1 %: ~1e-3
    for (int e = 0; e < c.model.num_elements(); ++e) CHECK(sim.element_state(e).hinge == 0);
  }

  SECTION("plateau, hinge at the root, elastic unloading") {
    SimulationOptions opt = no_gravity();
    opt.dt = 1e-3;
    Simulation<AsiGaussTimoshenko> sim(c.model, Newmark::paper(EquilibriumMode::iterate), opt);
    const int sp = sim.add_support_spring(c.tip, 1, 1e3 * kel, 2.5 * dy);
    REQUIRE(sim.solve_static(50, 50, 1e-10).converged);
    const double F0 = sim.spring_force(sp), u0 = sim.displacement(c.tip).y();
    INFO("plateau P / (Mp/L) = " << F0 / Pc << " at v = " << u0 / dy << " v_y");
    CHECK(std::abs(F0 / Pc - 1) < 0.02);
    // The hinge is at the clamped end of the root element: hinge = -1 (its end xi = -1), and the
    // integration point moved to s = -xi_end = +1 so that the stress point sits on that end; the
    // other element of the pair returned to s = 0; no other element yielded.
    CHECK(sim.element_state(0).hinge == -1);
    CHECK(sim.element_state(0).s == 1.0);
    CHECK(sim.element_state(1).s == 0.0);
    for (int e = 1; e < c.model.num_elements(); ++e) CHECK(sim.element_state(e).hinge == 0);
    CHECK(std::abs(sim.section_forces_at(0, -1).Mz) == Approx(c.Mp()).epsilon(1e-4));

    // Unloading: solve_static ramps the targets from 0 to 1, so the unloading is a slow load-scale
    // history in time (quasi-static: 0.5 s against a first period of 0.7 ms of the propped beam, the
    // paper's dissipative Newmark damping the stiff spring's mode). The target goes back by 40 %.
    const double T = 0.5;
    sim.set_load_scale([T](double t) { return 1 - 0.4 * 0.5 * (1 - std::cos(pi * std::min(t / T, 1.0))); });
    sim.run_until(T);
    const double F1 = sim.spring_force(sp), u1 = sim.displacement(c.tip).y();
    const double slope = (F0 - F1) / (u0 - u1);
    INFO("unloaded to P / (Mp/L) = " << F1 / Pc << ", unloading slope / k_el = " << slope / kel);
    CHECK(F1 < 0.05 * Pc);
    CHECK(std::abs(slope / kel - 1) < 0.02);
    // The hinge closed and the integration points are back on the Gauss points of the pair.
    CHECK(sim.element_state(0).hinge == 0);
    CHECK(sim.element_state(0).s == Approx(-(1 - 2 / std::sqrt(3.0))).margin(1e-15));
    CHECK(sim.element_state(1).s == Approx(1 - 2 / std::sqrt(3.0)).margin(1e-15));
  }
}

TEST_CASE("a fixed-fixed beam under a central load collapses at 8 Mp / L", "[statics][plastic]") {
  // Mechanism: hinges at both ends and at mid-span, P_c = 8 Mp / L. One end slides axially (all its
  // DOFs fixed but the axial one) so that no catenary force stiffens the mechanism. The mid-span node
  // joins two members of 10 ASI-Gauss elements; displacement control as for the cantilever.
  const double L = 1.0;
  Model m;
  const int b = m.add_body("beam");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = m.add_material(Material::steel());
  const int a = m.add_node({0, 0, 0}, b), mid = m.add_node({L / 2, 0, 0}, b), d = m.add_node({L, 0, 0}, b);
  MemberOptions o;
  o.elements = 10;
  o.y_ref = Vec3::UnitY();
  const int left = m.add_member("left half", a, mid, sec, mat, o);
  const int right = m.add_member("right half", mid, d, sec, mat, o);
  m.fix(a);
  m.fix(d, ALL_DOFS & ~UX);
  const auto& s = m.sections()[sec];
  const double Mp = m.materials()[mat].sigma_y * s.Zpz, EI = m.materials()[mat].E * s.Iz;
  const double Pc = 8 * Mp / L, kel = 192 * EI / (L * L * L);
  const double dy = Pc / kel;

  Simulation<AsiGaussTimoshenko> sim(m, Newmark{}, no_gravity());
  const int sp = sim.add_support_spring(mid, 1, 1e3 * kel, 3 * dy);
  REQUIRE(sim.solve_static(120, 50, 1e-10).converged);
  const double P = sim.spring_force(sp);
  INFO("collapse P / (8 Mp/L) = " << P / Pc);
  CHECK(std::abs(P / Pc - 1) < 0.02);
  // Hinges: the first element of the left half at its clamped end, the last of the right half at the
  // sliding end, and at mid-span (the elements on either side, each at its mid-span end).
  const int l0 = m.member(left).first_element, r0 = m.member(right).first_element;
  CHECK(sim.element_state(l0).hinge == -1);
  CHECK(sim.element_state(r0 + 9).hinge == 1);
  CHECK((sim.element_state(l0 + 9).hinge == 1 || sim.element_state(r0).hinge == -1));
  int hinges = 0;
  for (int e = 0; e < m.num_elements(); ++e) hinges += sim.element_state(e).hinge != 0;
  CHECK(hinges <= 4);
  CHECK(std::abs(sim.displacement(d).x()) < 1e-3 * L);  // the slider moved little: no catenary
}

// solve_static switches the simulation to statics for its duration. An exception inside it (here: a
// rigid body, which statics cannot solve) must not leave it there: the next dynamic step is the step
// a fresh simulation takes.
TEST_CASE("an exception inside solve_static leaves the simulation dynamic", "[statics]") {
  auto build = [](Model& model) {
    Cantilever c({.length = 1.0, .elements = 4, .pairs = true});
    model = c.model;
    const int block = model.add_body("block");
    const int sec = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "tube"));
    const int mat = model.add_material(Material{});
    const int a = model.add_node({0, 1, 0.5}, block), b = model.add_node({0.5, 1, 0.5}, block);
    MemberOptions o;
    o.elements = 2;
    o.pairs = true;
    o.y_ref = Vec3::UnitY();
    model.add_member("bar", a, b, sec, mat, o);
    return block;
  };
  Model model;
  const int block = build(model);
  Simulation<AsiGaussTimoshenko> thrown(model);
  thrown.set_rigid(block);
  CHECK_THROWS_AS(thrown.solve_static(), SimulationError);
  Simulation<AsiGaussTimoshenko> fresh(model);
  fresh.set_rigid(block);
  REQUIRE_NOTHROW(thrown.step());
  fresh.step();
  for (int n = 0; n < model.num_nodes(); ++n) {
    CHECK(thrown.position(n) == fresh.position(n));
    CHECK(thrown.velocity(n) == fresh.velocity(n));
  }
}

// ---- load control that stops, displacement control, arc-length ----

TEST_CASE("displacement control gives the cantilever's tip stiffness", "[statics][displacement-control]") {
  // A tip load P_ref (the reference load) and the tip driven to v: the load factor is k v / P_ref with
  // k = 1 / (L^3/(3EI) + L/(kGA)), exact for ASI-Gauss pairs (first test). v = 1e-6 L keeps the
  // geometric nonlinearity (~(v/L)^2) below round-off, so 1e-9 bounds the comparison.
  for (int n : {2, 8}) {
    for (double L : {0.5, 1.5}) {
      const Cantilever c({.length = L, .elements = n, .pairs = true});
      const double k = 1.0 / (c.bending_flexibility() + c.shear_flexibility());
      const double P_ref = 100, v = 1e-6 * L;
      Simulation<AsiGaussTimoshenko> sim(c.model, Newmark{}, no_gravity());
      sim.set_nodal_load(c.tip, (Vec6() << 0, P_ref, 0, 0, 0, 0).finished());
      const StaticPath path = sim.solve_static_displacement(c.tip, 1, v, 4, 50, 1e-12);
      REQUIRE(path.converged);
      REQUIRE(path.points.size() == 5);
      for (size_t i = 1; i < path.points.size(); ++i) {
        const auto& p = path.points[i];
        INFO("L = " << L << ", elements " << n << ", increment " << i << ": lambda P_ref / (k v) - 1 = "
                    << p.load_factor * P_ref / (k * p.displacement) - 1);
        CHECK(p.displacement == Approx(v * i / 4).epsilon(1e-12));
        CHECK(std::abs(p.load_factor * P_ref / (k * p.displacement) - 1) < 1e-9);
      }
      CHECK(sim.load_factor() == path.load_factor());
    }
  }
}

namespace {

// A fixed-base portal frame in the X-Y plane: columns of height h, a beam of span l, one square tube
// everywhere (Mp the same in every member). Reference loads: H along X at the top of the left column
// and V down at mid-span, scaled so that the combined mechanism (hinges at both bases, under the load
// and at the right end of the beam) collapses at load factor 1:
//     H h + V l / 2 = 6 Mp,  with H h = r c, V l / 2 = c, c = 6 Mp / (1 + r).
// Upper bounds: the beam mechanism (V l / 2 = 4 Mp) at 4 / c Mp = 2 (1 + r) / 3 and the sway mechanism
// (H h = 4 Mp) at 2 (1 + r) / (3 r); the combined one governs (is the smallest) for 1/2 < r < 2.
// A yield stress of 24.5 MPa (a tenth of the steel's) keeps the deflections at collapse, hence the
// second-order (P-delta) effects that the first-order closed form ignores, near 0.2 %. The axial
// forces lower the columns' plastic moment (N/N0 ~ 0.05: (N/N0)^2 ~ 0.3 %).
struct Portal {
  Model model;
  int base_l = 0, top_l = 0, mid = 0, top_r = 0, base_r = 0;
  double h = 1, l = 1, Mp = 0, H = 0, V = 0;
  Portal(double height, double span, double r, int elements = 8) : h(height), l(span) {
    const int b = model.add_body("portal");
    const int sec = model.add_section(Section::hollow_rectangle(0.04, 0.04, 0.002, "40 x 40 x 2"));
    Material steel;
    steel.sigma_y = 24.5e6;
    const int mat = model.add_material(steel);
    base_l = model.add_node({0, 0, 0}, b);
    top_l = model.add_node({0, h, 0}, b);
    mid = model.add_node({l / 2, h, 0}, b);
    top_r = model.add_node({l, h, 0}, b);
    base_r = model.add_node({l, 0, 0}, b);
    MemberOptions column, beam;
    column.elements = beam.elements = elements;
    column.y_ref = -Vec3::UnitX();
    beam.y_ref = Vec3::UnitY();
    model.add_member("left column", base_l, top_l, sec, mat, column);
    model.add_member("beam, left half", top_l, mid, sec, mat, beam);
    model.add_member("beam, right half", mid, top_r, sec, mat, beam);
    model.add_member("right column", base_r, top_r, sec, mat, column);
    model.fix(base_l);
    model.fix(base_r);
    Mp = steel.sigma_y * model.sections()[sec].Zpz;
    const double c = 6 * Mp / (1 + r);
    H = r * c / h;
    V = 2 * c / l;
  }
  template <class Sim>
  void load(Sim& sim, double scale = 1) const {
    sim.set_nodal_load(top_l, (Vec6() << scale * H, 0, 0, 0, 0, 0).finished());
    sim.set_nodal_load(mid, (Vec6() << 0, -scale * V, 0, 0, 0, 0).finished());
  }
  // The sway at load factor 1 of the elastic frame (one linear solve): the scale of the path.
  double elastic_sway() const {
    Simulation<AsiGaussTimoshenko> sim(model, Newmark{}, no_gravity());
    load(sim, 1e-6);
    REQUIRE(sim.solve_static(1, 50, 1e-12).converged);
    return 1e6 * sim.displacement(top_l).x();
  }
};

struct PortalCase {
  double h, l, r;
};
constexpr PortalCase portal_cases[] = {{1.0, 1.0, 1.0}, {0.8, 1.6, 0.7}, {1.2, 0.9, 1.6}};

}  // namespace

TEST_CASE("arc-length finds the portal frame's combined mechanism, H h + V l/2 = 6 Mp", "[statics][arc-length]") {
  for (const auto& pc : portal_cases) {
    const Portal p(pc.h, pc.l, pc.r);
    const double u1 = p.elastic_sway();
    Simulation<AsiGaussTimoshenko> sim(p.model, Newmark{}, no_gravity());
    p.load(sim);
    ArcLengthOptions o;
    o.node = p.top_l;
    o.dof = 0;
    o.max_displacement = 6 * u1;
    o.max_increments = 600;
    const StaticPath path = sim.solve_static_arc_length(o);
    INFO("h = " << pc.h << ", l = " << pc.l << ", r = " << pc.r << ": " << path.reason << "; " << path.points.size() - 1
                << " increments, " << path.iterations << " iterations; peak load factor " << path.peak_load_factor()
                << ", last " << path.load_factor() << " at sway " << path.points.back().displacement / u1 << " u1");
    CHECK(path.converged);
    CHECK(std::abs(path.peak_load_factor() - 1) < 0.02);
    CHECK(path.points.back().displacement >= 6 * u1);  // along the mechanism, past the peak
    CHECK(std::abs(path.load_factor() - 1) < 0.02);      // P-delta: the plateau descends slowly
  }
}

TEST_CASE("displacement control finds the portal frame's combined mechanism", "[statics][displacement-control]") {
  for (const auto& pc : portal_cases) {
    const Portal p(pc.h, pc.l, pc.r);
    const double u1 = p.elastic_sway();
    Simulation<AsiGaussTimoshenko> sim(p.model, Newmark{}, no_gravity());
    p.load(sim);
    const StaticPath path = sim.solve_static_displacement(p.top_l, 0, 6 * u1, 120, 50, 1e-9);
    INFO("h = " << pc.h << ", l = " << pc.l << ", r = " << pc.r << ": " << path.reason << "; " << path.iterations
                << " iterations; peak load factor " << path.peak_load_factor() << ", last " << path.load_factor());
    REQUIRE(path.converged);
    CHECK(std::abs(path.peak_load_factor() - 1) < 0.02);
    CHECK(std::abs(path.load_factor() - 1) < 0.02);  // on the plateau, which P-delta makes descend slowly
  }
}

TEST_CASE("load control past the collapse load stops with a reason in the last converged state", "[statics]") {
  // Loads 1.3 times the collapse loads in 20 increments: the collapse is at load factor 1/1.3 = 0.769,
  // so the increment to 0.75 is the last that can converge.
  for (const auto& pc : portal_cases) {
    const Portal p(pc.h, pc.l, pc.r);
    Simulation<AsiGaussTimoshenko> sim(p.model, Newmark{}, no_gravity());
    p.load(sim, 1.3);
    StaticResult res;
    REQUIRE_NOTHROW(res = sim.solve_static(20, 30, 1e-8));
    INFO("h = " << pc.h << ", l = " << pc.l << ", r = " << pc.r << ": " << res.reason << " (" << res.increments
                << " increments)");
    CHECK_FALSE(res.converged);
    CHECK_FALSE(res.reason.empty());
    CHECK(res.load_factor == Approx(res.increments / 20.0));
    CHECK(res.load_factor <= 1 / 1.3);
    CHECK(res.load_factor >= 0.6);
    CHECK(sim.load_factor() == res.load_factor);
    // The state is the converged one of that load factor: in equilibrium with the loads there ...
    const Vec6 f_top = sim.internal_force(p.top_l), f_mid = sim.internal_force(p.mid);
    CHECK(std::abs(f_top[0] - res.load_factor * 1.3 * p.H) < 1e-6 * p.H);
    CHECK(std::abs(f_mid[1] + res.load_factor * 1.3 * p.V) < 1e-6 * p.V);
    // ... and the one a solve stopping at that load factor reaches (the same increments).
    Simulation<AsiGaussTimoshenko> ref(p.model, Newmark{}, no_gravity());
    p.load(ref, 1.3 * res.load_factor);
    // (A tolerance of 1e-8: at 97.5 % of the collapse load the residual can stall near 1e-9.)
    REQUIRE(ref.solve_static(res.increments, 30, 1e-8).converged);
    // The two differ by the round-off of j/20 * 1.3 against j/15 * 0.975 in the loads and by the
    // Newton tolerance (measured up to 1.3e-10 of the sway; the failed increment's last iterate is off
    // by its whole diverged step): 1e-6.
    double diff = 0;
    for (int n = 0; n < p.model.num_nodes(); ++n) diff = std::max(diff, (sim.displacement(n) - ref.displacement(n)).norm());
    INFO("largest difference / sway = " << diff / ref.displacement(p.top_l).norm());
    CHECK(diff < 1e-6 * ref.displacement(p.top_l).norm());
    // A dynamic step from there works.
    REQUIRE_NOTHROW(sim.step());
  }
}

}  // namespace statics_tests
