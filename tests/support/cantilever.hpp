#pragma once
// The tests' cantilever: a steel member of the paper's 50 x 30 x 2 mm tube clamped at the origin, the
// fixture of the statics, dynamics, integrator, damping, concept and base-excitation tests (one
// definition, so that they check the same structure).
//
// Along X (the default) y_ref = Y puts the 50 mm side along Y: it bends about its strong axis in the X-Y
// plane (EI = E Iz). Vertical (along Z) it takes the default y_ref of a vertical member, global Y: the
// 50 mm side along Y, the 30 mm side along X (weak axis for an X load, E Iy; strong for Y, E Iz).
#include <furniture_fem/core/model.hpp>

#include <string>

namespace ffem_test {

struct CantileverOptions {
  double length = 1.0;           // m
  int elements = 8;
  bool pairs = true;             // ASI-Gauss pairs (MemberOptions::pairs, its default)
  double yield_stress = 245e6;   // Pa; 1e20 keeps it elastic
  bool vertical = false;         // along +Z instead of +X
};

struct Cantilever {
  furniture_fem::Model model;
  int body = 0, root = 0, tip = 0, section = 0, material = 0;
  double L = 1;

  explicit Cantilever(const CantileverOptions& o = {}) : L(o.length) {
    using namespace furniture_fem;
    body = model.add_body("cantilever");
    section = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "50 x 30 x 2"));
    Material steel;
    steel.sigma_y = o.yield_stress;
    material = model.add_material(steel);
    root = model.add_node({0, 0, 0}, body);
    tip = model.add_node(o.vertical ? Vec3(0, 0, L) : Vec3(L, 0, 0), body);
    MemberOptions m;
    m.elements = o.elements;
    m.pairs = o.pairs;
    if (!o.vertical) m.y_ref = Vec3::UnitY();
    model.add_member("beam", root, tip, section, material, m);
    model.fix(root);
  }

  const furniture_fem::Section& sec() const { return model.sections()[section]; }
  const furniture_fem::Material& mat() const { return model.materials()[material]; }
  double EI() const { return mat().E * sec().Iz; }  // strong axis
  double GAs() const { return mat().G() * sec().Asy; }
  double Mp() const { return mat().sigma_y * sec().Zpz; }
  double bending_flexibility() const { return L * L * L / (3 * EI()); }  // tip deflection per unit tip load
  double shear_flexibility() const { return L / GAs(); }

  // Sets every node but the root moving in the shape of the tip-loaded static deflection along Y,
  // w(xi) = (3 xi^2 - xi^3) / 2 at xi = x / L (the rotations its slope), with the tip at v_tip (m/s).
  // A horizontal cantilever of length 1 (the tests' free-vibration cases).
  template <class Sim>
  void release_in_static_shape(Sim& sim, double v_tip) const {
    for (int n = 0; n < model.num_nodes(); ++n) {
      const double xi = model.node(n).X.x();
      if (n != root)
        sim.set_velocity(n, (furniture_fem::Vec6() << 0, v_tip * (3 * xi * xi - xi * xi * xi) / 2, 0, 0, 0,
                             v_tip * (3 * xi - 1.5 * xi * xi))
                                .finished());
    }
  }
};

}  // namespace ffem_test
