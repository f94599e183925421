// Base excitation in the full solver (docs/contact/contact.md: the table frame, every mass gets
// -m a_table), on a fixed elastic cantilever without contact:
//  8. a constant table acceleration bends it like a uniform load -rho A a (closed form); a record
//     scaled by 0.5 gives exactly half the response (linearity); a 1-D record and the same record as
//     the X component of a 3-D motion give identical histories; the Y component of a 3-D record
//     drives only Y; the three components superpose.
// No CGAL here: this file includes only the solver and the excitation module.
#include <catch2/catch.hpp>

#include <furniture_fem/excitation/excitation.hpp>
#include <furniture_fem/core/simulation.hpp>

#include "../support/cantilever.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace furniture_fem;
using Catch::Matchers::WithinRel;

namespace base_excitation_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A 1 m vertical cantilever of 50 x 30 x 2 tube, clamped at the origin, 20 ASI-Gauss elements
// (tests/support/cantilever.hpp). Vertical members take y_ref = global Y: the 50 mm side (local y) lies
// along Y, the 30 mm side (local z) along X. Its principal axes are X and Y, so it is symmetric for both:
// an X load bends it in X only (weak axis, E Iy), a Y load in Y only (strong axis, E Iz). First modes
// 35 Hz (X) and 52 Hz (Y).
ffem_test::Cantilever post() { return ffem_test::Cantilever({.elements = 20, .yield_stress = 1e20, .vertical = true}); }

// Tip displacement history (relative to the table) under a table motion, paper Newmark, dt 1 ms,
// no gravity (so that nothing but the excitation loads it).
std::vector<Vec3> tip_history(const std::function<Vec3(double)>& table, double t_end, double mass_damping = 0) {
  const ffem_test::Cantilever c = post();
  SimulationOptions o;
  o.dt = 1e-3;
  o.gravity.setZero();
  o.mass_damping = mass_damping;
  Simulation<AsiGaussTimoshenko> sim(c.model, Newmark::paper(), o);
  sim.set_table_acceleration(table);
  std::vector<Vec3> h;
  sim.run_until(t_end, [&](const auto& s, const StepInfo&) { h.push_back(s.displacement(c.tip)); });
  return h;
}

double max_abs(const std::vector<Vec3>& h, int axis) {
  double m = 0;
  for (const Vec3& u : h) m = std::max(m, std::abs(u[axis]));
  return m;
}

Record ground(std::uint64_t seed, double pga, double period) {
  SyntheticOptions o;
  o.seed = seed;
  o.duration = 2.0;
  o.dt = 0.01;
  o.pga = pga;
  o.predominant_period = period;
  return synthetic_motion(o);
}

Record zeros_like(const Record& r) {
  Record z = r;
  std::fill(z.acc.begin(), z.acc.end(), 0.0);
  return z;
}

void report(const char* format, double a = 0, double b = 0, double c = 0, double d = 0) {
  if (!std::getenv("FFEM_REPORT")) return;
  std::printf(format, a, b, c, d);
  std::printf("\n");
}

}  // namespace

TEST_CASE("a constant table acceleration bends a cantilever like the uniform load -rho A a", "[contact_dynamics][excitation]") {
  // In the table frame every mass gets -m a: a table accelerating at +a along X loads the cantilever
  // with q = -rho A a per metre, so its tip lags behind the table by
  //     u = q L^4 / (8 E Iy) + q L^2 / (2 G Asz)          (Timoshenko: bending + shear)
  // The solver lumps the mass at the nodes, P_i = q h (q h / 2 at the tip), and for those point loads
  // the closed form is the sum of tip deflections of a cantilever under a load at a_i,
  //     u = sum P_i (a_i^2 (3 L - a_i) / (6 E Iy) + a_i / (G Asz)),
  // 0.083% above the uniform load's (the trapezoid rule's h^2 / 3). Mass-proportional damping
  // (C = 100 M, 23% on the first mode) lets it settle; after 1 s the transient is below 1e-9.
  const double a = 2.0;
  const auto h = tip_history([=](double) { return Vec3(a, 0, 0); }, 1.0, 100.0);
  const Section s = Section::hollow_rectangle(0.05, 0.03, 0.002);
  const Material m = Material::steel();
  const double q = -m.rho * s.A * a, L = 1.0, EI = m.E * s.Iy, GA = m.G() * s.Asz;
  const double uniform = q * std::pow(L, 4) / (8 * EI) + q * L * L / (2 * GA);
  const int n = 20;
  double lumped = 0;
  for (int i = 1; i <= n; ++i) {
    const double ai = L * i / n, Pi = q * L / n * (i == n ? 0.5 : 1.0);
    lumped += Pi * (ai * ai * (3 * L - ai) / (6 * EI) + ai / GA);
  }
  const Vec3 u = h.back();
  report("T8 constant table acceleration %.1f m/s^2: tip u_x %.8e m; lumped-load closed form %.8e m (ratio - 1 = %.2e)", a,
         u.x(), lumped, u.x() / lumped - 1);
  report("T8   uniform-load closed form %.8e m (ratio - 1 = %.2e)", uniform, u.x() / uniform - 1);
  CHECK(u.x() < 0);  // the tip lags behind the accelerating table
  // ASI-Gauss pairs are exact for loads at their end nodes; the loads at the pairs' middle nodes
  // leave 3.9e-4 (measured); the uniform load's closed form is 0.12% away (the lumping's 0.083% and
  // that).
  CHECK_THAT(u.x(), WithinRel(lumped, 1e-3));
  CHECK_THAT(u.x(), WithinRel(uniform, 2e-3));
  CHECK(std::abs(u.y()) < 1e-12 * std::abs(u.x()));
}

TEST_CASE("base excitation: linearity in the level, 1-D against 3-D, and one component drives one direction",
          "[contact_dynamics][excitation]") {
  // Records: synthetic ground motions (Kanai-Tajimi, 2 s), PGA 1 m/s^2 (tip amplitude 0.1 mm: the
  // corotational geometry's nonlinearity is then of order u/L = 1e-4 of the response, relative).
  const Record rx = ground(11, 1.0, 0.1), ry = ground(12, 1.0, 0.08), rz = ground(13, 0.5, 0.05);
  const Record zero = zeros_like(rx);
  const double t_end = 2.0;
  auto run = [&](const TableMotion& motion) { return tip_history([motion](double t) { return motion(t); }, t_end); };

  const auto full = run(TableMotion::one_d(rx));
  const auto half = run(TableMotion::one_d(rx).scaled(0.5));
  const auto small = run(TableMotion::one_d(rx).scaled(0.1));
  const auto small_half = run(TableMotion::one_d(rx).scaled(0.05));
  const auto as_3d = run(TableMotion::three_d(rx, zero, zero));
  const auto y_only = run(TableMotion::three_d(zero, ry, zero));
  const auto z_only = run(TableMotion::three_d(zero, zero, rz));
  const auto all = run(TableMotion::three_d(rx, ry, rz));
  REQUIRE(full.size() == half.size());

  // Linearity: u(0.5 a) = 0.5 u(a) up to the corotational geometry's nonlinearity, which is
  // quadratic in the amplitude: relative to the peak it is of order u/L (4e-5 here) and falls in
  // proportion to the level. Checked at PGA 1 and 0.1 m/s^2: the relative residual must fall 10x.
  const double peak = max_abs(full, 0), peak_small = max_abs(small, 0);
  double lin = 0, lin_small = 0, same = 0, cross = 0, sup = 0;
  for (size_t i = 0; i < full.size(); ++i) {
    lin = std::max(lin, (half[i] - 0.5 * full[i]).norm());
    lin_small = std::max(lin_small, (small_half[i] - 0.5 * small[i]).norm());
    same = std::max(same, (as_3d[i] - full[i]).norm());
    sup = std::max(sup, (all[i] - (full[i] + y_only[i] + z_only[i])).norm());
  }
  cross = max_abs(y_only, 0);
  const double peak_y = max_abs(y_only, 1), axial_y = max_abs(y_only, 2);
  report("T8 linearity: peak tip u_x %.3e m, max |u(0.5 a) - 0.5 u(a)| / peak = %.2e; at a tenth of the level %.2e "
         "(ratio %.2f)",
         peak, lin / peak, lin_small / peak_small, (lin / peak) / (lin_small / peak_small));
  report("T8 1-D vs 3-D(x, 0, 0): max difference %.1e m (bitwise)", same);
  report("T8 Y-only 3-D record: peak u_y %.3e m, peak |u_x| %.1e m, peak |u_z| %.2e m (second-order shortening)", peak_y, cross,
         axial_y);
  report("T8 superposition x + y + z: max deviation / peak = %.2e", sup / std::max(peak, peak_y));
  CHECK(peak > 1e-5);
  CHECK(lin < 1e-4 * peak);                                 // 5e-6 measured
  CHECK((lin / peak) / (lin_small / peak_small) > 8);       // 10 if the residual is purely quadratic
  CHECK((lin / peak) / (lin_small / peak_small) < 12);
  CHECK(same == 0.0);  // the same numbers enter the same operations
  // Y drives only Y: the X response stays at round-off; the Z response is the shortening of the
  // bent post, of order u_y^2 / L (plus the Z component's absence: nothing else drives it).
  CHECK(peak_y > 1e-5);
  CHECK(cross < 1e-12 * peak_y);
  CHECK(axial_y < 10 * peak_y * peak_y);
  // Superposition of the three components, to the same nonlinearity bound (1.4e-5 measured).
  CHECK(sup < 1e-4 * std::max(peak, peak_y));
}

}  // namespace base_excitation_tests
