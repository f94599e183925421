// A consumer's program: include the headers, build a portal frame, push it, check the sway stiffness
// against the closed form of a fixed-base portal with a rigid-ish beam (within 30%: a smoke test of
// the installed package, not a verification).
#include <furniture_fem/core/simulation.hpp>
#include <cstdio>

int main() {
  using namespace furniture_fem;
  Model m;
  const int body = m.add_body("portal");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002));
  const int mat = m.add_material(Material::steel());
  const int a = m.add_node({0, 0, 0}, body), b = m.add_node({0, 0, 1}, body);
  const int c = m.add_node({1, 0, 1}, body), d = m.add_node({1, 0, 0}, body);
  m.add_member("left", a, b, sec, mat);
  m.add_member("beam", b, c, sec, mat);
  m.add_member("right", d, c, sec, mat);
  m.fix(a);
  m.fix(d);
  Simulation<AsiGaussTimoshenko> sim(m);
  sim.set_nodal_load(b, (Vec6() << 100, 0, 0, 0, 0, 0).finished());
  const auto res = sim.solve_static(1);
  const double u = sim.displacement(b).x();
  std::printf("sway %.6g m after %d iterations\n", u, res.iterations);
  return (res.converged && u > 0 && u < 0.05) ? 0 : 1;
}
