// step-3: a portal frame pushed sideways to collapse, and the plastic mechanism that limits its load.
//
// What is new relative to step-2: material nonlinearity. Every ASI-Gauss element checks the fully
// plastic condition at its ends; when an end yields, the element moves its integration point so that
// its stress evaluation point sits exactly on that end (a plastic hinge), and the sectional forces
// there follow the yield surface. Displacement control (a stiff support spring whose target grows with
// the load factor) carries the push-over past the limit load, where force control would fail.
//
// The frame: two 1 m columns with fixed bases and a 1 m beam in the X-Z plane, all 50 x 30 x 2 mm
// steel tubes in their default orientation (MemberOptions::y_ref left at zero): the beam bends about
// its strong axis (the 50 mm side vertical), the columns about their weak axis (the 30 mm side along
// the push), as the legs of a cabinet pushed along its width. Pushed along X at the top of the left
// column, the frame fails by the sway mechanism with hinges at the bottom and top of both columns
// (the beam is stronger, so the joints yield in the columns):
//     P_c = 4 Mp / h,  Mp = sigma_y Zp of the columns' weak axis.
#include <furniture_fem/core/simulation.hpp>

#include <cstdio>
#include <string>
#include <vector>

using namespace furniture_fem;

int main() {
  const double h = 1.0, b = 1.0;
  Model model;
  const int body = model.add_body("portal");
  const int tube = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "50 x 30 x 2"));
  const int steel = model.add_material(Material::steel());
  const int base_l = model.add_node({0, 0, 0}, body), top_l = model.add_node({0, 0, h}, body);
  const int top_r = model.add_node({b, 0, h}, body), base_r = model.add_node({b, 0, 0}, body);
  // Default orientation: a member's local y is global Z (global Y for vertical members). The
  // columns' local y is then Y, so a sway along X bends them in their local x-z plane, about the
  // weak axis (Iy, Zpy); the beam's local y is Z: in-plane bending about its strong axis (Iz, Zpz).
  MemberOptions opts;
  opts.elements = 10;  // five ASI-Gauss pairs per member
  model.add_member("left column", base_l, top_l, tube, steel, opts);
  model.add_member("beam", top_l, top_r, tube, steel, opts);
  model.add_member("right column", base_r, top_r, tube, steel, opts);
  model.fix(base_l);
  model.fix(base_r);

  const Section& s = model.sections()[tube];
  const Material& m = model.materials()[steel];
  const double Mp = m.sigma_y * s.Zpy, Mp_beam = m.sigma_y * s.Zpz, Pc = 4 * Mp / h;
  // Elastic sway stiffness of a fixed-base portal (shear and axial flexibility neglected):
  // k = 24 EI_c/h^3 (6 r + 1)/(6 r + 4), r = (I_b/b)/(I_c/h) the beam-to-column stiffness ratio.
  const double EIc = m.E * s.Iy, r = (s.Iz / b) / (s.Iy / h);
  const double k_el = 24 * EIc / (h * h * h) * (6 * r + 1) / (6 * r + 4);
  std::printf("Portal frame h = b = 1 m, 50 x 30 x 2 mm tubes\n");
  std::printf("Columns (weak axis): Mp = %.1f N m; beam (strong axis): Mp = %.1f N m\n", Mp, Mp_beam);
  std::printf("Sway mechanism: P_c = 4 Mp / h = %.1f N; elastic sway stiffness k = %.4g N/m\n\n", Pc, k_el);

  SimulationOptions options;
  options.gravity.setZero();  // a pure push-over: no vertical load, no P-delta
  auto hinge_names = [&](const auto& sim) {
    std::string out;
    for (int e = 0; e < model.num_elements(); ++e) {
      const int end = sim.element_state(e).hinge;
      if (end == 0) continue;
      const auto& el = model.elements()[e];
      const Member& mem = model.member(el.member);
      const int node = end < 0 ? el.n1 : el.n2;
      char buf[160];
      std::snprintf(buf, sizeof buf, "  %s, element %d, at its %s end (x = %.2f m, z = %.2f m), s = %+.0f\n",
                    mem.name.c_str(), e - mem.first_element, end < 0 ? "first" : "second", model.node(node).X.x(),
                    model.node(node).X.z(), sim.element_state(e).s);
      out += buf;
    }
    return out.empty() ? std::string("  none\n") : out;
  };

  // Each point of the curve is a fresh static solve from the unloaded frame: the loading is
  // monotonic, so the path up to each target is the same, and every solve ramps its target in
  // increments of about 1 mm.
  std::printf("Load-displacement curve (u: sway of the loaded joint, P: the push)\n");
  std::printf("%10s %12s %9s %12s  %s\n", "u (mm)", "P (N)", "P / P_c", "P / (k u)", "hinges");
  const double u_max = 0.06;
  double P_last = 0;
  std::string hinges_last;
  for (int i = 1; i <= 12; ++i) {
    const double target = u_max * i / 12;
    Simulation<AsiGaussTimoshenko> sim(model, Newmark{}, options);
    const int spring = sim.add_support_spring(top_l, 0, 1e3 * k_el, target);
    const auto res = sim.solve_static(static_cast<int>(target * 1000) + 2, 60, 1e-9);
    if (!res.converged) {
      std::printf("%10.1f  did not converge (residual %.2e)\n", target * 1e3, res.residual);
      continue;
    }
    const double u = sim.displacement(top_l).x(), P = sim.spring_force(spring);
    std::printf("%10.2f %12.1f %9.4f %12.4f  %d\n", u * 1e3, P, P / Pc, P / (k_el * u),
                [&] { int n = 0; for (int e = 0; e < model.num_elements(); ++e) n += sim.element_state(e).hinge != 0; return n; }());
    P_last = P;
    hinges_last = hinge_names(sim);
  }
  std::printf("\nPlastic hinges at u = %.0f mm (the integration point s moved to the hinged end):\n%s", u_max * 1e3,
              hinges_last.c_str());
  std::printf("Collapse load: %.1f N = %.4f P_c (plastic mechanism 4 Mp / h = %.1f N)\n", P_last, P_last / Pc, Pc);
  return 0;
}
