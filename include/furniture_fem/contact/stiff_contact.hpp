#pragma once
// The `stiff` contact rule from an item's own mass, footprint and inertia: nothing to choose per item
// (docs/contact/contact.md, "stiff"). Used by the scenes (contact.law "stiff") and by the tests.
#include <furniture_fem/contact/contact_laws.hpp>
#include <furniture_fem/core/model.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace furniture_fem {

// The body's nodes at its lowest level (within 1 mm): those that rest on the floor.
inline std::vector<int> resting_nodes(const Model& model, int body) {
  double z_min = std::numeric_limits<double>::infinity();
  for (int n : model.body(body).nodes) z_min = std::min(z_min, model.node(n).X.z());
  std::vector<int> resting;
  for (int n : model.body(body).nodes)
    if (model.node(n).X.z() <= z_min + 1e-3) resting.push_back(n);
  return resting;
}

// The normal damping ratio per resting node that damps the item's rocking on its resting springs as
// well as its vertical motion. Springs k and dashpots c at offsets x_i from the footprint centre give a
// rocking mode of stiffness n k <x^2> and damping n c <x^2> against the inertia I about the footprint
// centre, so its damping ratio is zeta_node sqrt(m <x^2> / I): 0.25 for a 1.2 m frame on a 0.45 m
// footprint at zeta_node 1, whose rocking then overshoots a suddenly applied load and tips it 2 % below
// g b/h (measured). The ratio that makes rocking critical is therefore sqrt(I / (m <x^2>)), at least 1;
// it is capped at 2: the vertical mode at 2.5 um (omega dt = 2 at dt 1 ms) then has zeta omega dt = 4,
// and at 3 the step's trapezoidal dashpot rings (a resting block keeps 3 mm/s, measured). At 2 every
// block tested holds to 0.99 g b/h (rigid) and 0.98 (frames). A footprint without extent along an axis
// (all resting nodes on one line) does not count for that axis.
inline double rocking_damping_ratio(const Model& model, int body, const std::vector<int>& resting) {
  if (resting.empty()) return 1.0;
  Vec3 centre = Vec3::Zero();
  for (int n : resting) centre += model.node(n).X;
  centre /= double(resting.size());
  Vec3 spread = Vec3::Zero();  // <x^2>, <y^2> of the resting nodes about the centre
  for (int n : resting) spread += (model.node(n).X - centre).cwiseAbs2();
  spread /= double(resting.size());
  const double mass = model.body_mass(body);
  const Mat3 I = model.body_inertia(body, centre);
  double worst = 1.0;
  // Rocking about x moves the nodes by their y offsets, about y by their x offsets.
  for (const auto& [axis, arm2] : {std::pair{0, spread.y()}, std::pair{1, spread.x()}})
    if (arm2 > 1e-8) worst = std::max(worst, std::sqrt(I(axis, axis) / (mass * arm2)));
  return std::min(worst, 2.0);
}

// The lightest lumped node mass of a body: half of each member element's mass at its two nodes, plus
// point masses.
inline double lightest_node_mass(const Model& model, int body) {
  std::vector<double> m(model.num_nodes(), 0.0);
  for (int e : model.body(body).elements) {
    const auto& el = model.elements()[e];
    const double half = 0.5 * el.line_mass * model.element_length(e);
    m[el.n1] += half;
    m[el.n2] += half;
  }
  for (const auto& pm : model.point_masses()) m[pm.node] += pm.mass;
  double lightest = std::numeric_limits<double>::infinity();
  for (int n : model.body(body).nodes)
    if (m[n] > 0) lightest = std::min(lightest, m[n]);
  return lightest;
}

// The `stiff` law between two items. Item-item contact is evaluated explicitly (outside the implicit
// step, docs/contact/implicit_contact.md), and a spring or dashpot applied explicitly is stable only
// while it is small against the node it acts on: the item's floor spring (2.5 um under its weight)
// is ten times past that for a cabinet's nodes at dt 1 ms, and configuration 3 blew up where the
// upper cabinet stands on the lower one (2026-11). So between items the spring is capped at
// k = m / (4 dt^2) (omega dt = 0.5 for a node of mass m against a fixed surface) and the dashpot at
// c = 0.2 m / dt (c dt / m = 0.2, against the explicit dashpot's limit 2 / (1 + 2 gamma), 0.75 for
// the paper's Newmark; zeta 0.2). A node in several pairs adds their terms: hence the margins.
// Stacked items then sink by about a millimetre instead of micrometres.
inline void cap_for_explicit_pairs(ContactParams& p, double lightest_node_mass, double dt) {
  if (!(lightest_node_mass > 0) || !std::isfinite(lightest_node_mass) || !(dt > 0)) return;
  const double k_max = 0.25 * lightest_node_mass / (dt * dt), c_max = 0.2 * lightest_node_mass / dt;
  if (p.k_lin > k_max) {
    p.k_lin = k_max;
    p.k_hc = k_max / std::sqrt(ContactParams::stiff_resting_penetration);
  }
  p.c_lin = std::min(p.c_lin, c_max);
}

// Sets the `stiff` law's spring and damping of one body (ContactParams::set_stiff).
inline void set_stiff_contact(const Model& model, int body, ContactParams& p) {
  const std::vector<int> resting = resting_nodes(model, body);
  p.set_stiff(model.body_mass(body), int(resting.size()), rocking_damping_ratio(model, body, resting));
}

}  // namespace furniture_fem
