// step-1: a cantilever against its closed forms: the first furniture_fem program.
//
// What this step shows: how a model is built (a body, a section, a material, nodes, a member split
// into elements), how the solver is composed at compile time (Simulation<Element>), and how a static
// solution is obtained (solve_static: load increments with full Newton). Three results are compared
// with closed forms:
//   1. one ASI-Gauss pair is exact for a tip load: P L^3/(3 E I) + P L/(k G A);
//   2. the conventional one-point element (integration point at the centre) needs refinement: it gives
//      (1 - 1/(4 n^2)) of the bending deflection with n elements;
//   3. under large loads the beam follows the elastica (Bisshopp & Drucker 1945), because the solver
//      is geometrically exact (corotational element frames) even though each element is linear.
#include <furniture_fem/core/simulation.hpp>

#include <cstdio>

using namespace furniture_fem;

namespace {

// The model: a 1 m cantilever along X, clamped at the origin, made of the paper's 50 x 30 x 2 mm
// steel tube. y_ref = Y puts the section's local y (its 50 mm side) along global Y, so a load along Y
// bends it about its strong axis, with E Iz.
struct Cantilever {
  Model model;
  int root = 0, tip = 0;
  Cantilever(int elements, bool pairs) {
    const int body = model.add_body("cantilever");
    const int tube = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "50 x 30 x 2"));
    Material steel;        // E 206 GPa, nu 0.3, rho 7850 kg/m^3 ...
    steel.sigma_y = 1e20;  // ... and, for this step, no yielding (step-3 is about plasticity)
    const int mat = model.add_material(steel);
    root = model.add_node({0, 0, 0}, body);
    tip = model.add_node({1, 0, 0}, body);
    MemberOptions opts;
    opts.elements = elements;  // add_member creates the intermediate nodes
    opts.pairs = pairs;        // ASI-Gauss elements come in pairs
    opts.y_ref = Vec3::UnitY();
    model.add_member("beam", root, tip, tube, mat, opts);
    model.fix(root);  // all six DOFs
  }
};

// Tip deflection along Y under a tip load P along Y (a fixed-direction nodal load).
template <class Element>
Vec3 tip_position(const Cantilever& c, double P, int increments) {
  SimulationOptions options;
  options.gravity.setZero();  // only the tip load
  Simulation<Element> sim(c.model, Newmark{}, options);
  sim.set_nodal_load(c.tip, (Vec6() << 0, P, 0, 0, 0, 0).finished());
  const auto res = sim.solve_static(increments, 60, 1e-10);
  if (!res.converged) std::printf("  (not converged: residual %.2e)\n", res.residual);
  return sim.position(c.tip);
}

}  // namespace

int main() {
  const Section tube = Section::hollow_rectangle(0.05, 0.03, 0.002);
  const Material steel;
  const double L = 1.0, EI = steel.E * tube.Iz, kGA = steel.G() * tube.Asy;
  std::printf("Cantilever L = 1 m, 50 x 30 x 2 mm: EI = %.5g N m^2, kGA = %.5g N\n\n", EI, kGA);

  // 1. A small load (0.01 N) keeps the response linear: the exact answer is bending + shear.
  const double P = 0.01, exact = P * L * L * L / (3 * EI) + P * L / kGA;
  const double v1 = tip_position<AsiGaussTimoshenko>(Cantilever(2, true), P, 1).y();
  std::printf("1. One ASI-Gauss pair, P = %.2g N:\n", P);
  std::printf("   tip deflection %.10e m, closed form %.10e m, ratio %.12f\n\n", v1, exact, v1 / exact);

  // 2. Refinement: the one-point element converges as 1 - 1/(4 n^2); ASI-Gauss is exact at every n.
  std::printf("2. Tip deflection / closed form, bending part only (shear part subtracted):\n");
  std::printf("   %4s %14s %14s %14s\n", "n", "ASI-Gauss", "one-point", "1 - 1/(4n^2)");
  for (int n : {2, 4, 8, 16}) {
    const double shear = P * L / kGA, bending = P * L * L * L / (3 * EI);
    const double va = tip_position<AsiGaussTimoshenko>(Cantilever(n, true), P, 1).y();
    const double vc = tip_position<ConventionalTimoshenko>(Cantilever(n, false), P, 1).y();
    std::printf("   %4d %14.10f %14.10f %14.10f\n", n, (va - shear) / bending, (vc - shear) / bending,
                1 - 1.0 / (4.0 * n * n));
  }

  // 3. Large deflections: the load is fixed in direction, the beam curls. Reference: the elastica
  // (no shear, no stretch; both are below 0.5 % here), tip deflection v/L and shortening (L - x)/L.
  std::printf("\n3. Large deflection, 20 ASI-Gauss elements, against the elastica:\n");
  std::printf("   %10s %10s %10s %12s %12s\n", "PL^2/EI", "v/L", "elastica", "(L-x)/L", "elastica");
  const double alpha[] = {1, 2, 5, 10}, v_ref[] = {0.30172, 0.49346, 0.71379, 0.81061},
               u_ref[] = {0.05643, 0.16064, 0.38763, 0.55500};
  for (int i = 0; i < 4; ++i) {
    const Vec3 x = tip_position<AsiGaussTimoshenko>(Cantilever(20, true), alpha[i] * EI / (L * L),
                                                   static_cast<int>(2 * alpha[i]) + 2);
    std::printf("   %10.0f %10.5f %10.5f %12.5f %12.5f\n", alpha[i], x.y() / L, v_ref[i], (L - x.x()) / L, u_ref[i]);
  }
  return 0;
}
