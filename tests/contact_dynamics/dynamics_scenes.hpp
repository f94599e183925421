#pragma once
// Scenes shared by the contact-dynamics tests: box frames of the paper's 50 x 30 x 2 mm steel tube
// standing on the floor, contact parameters, and measurements taken from a running Simulation.
//
// Geometry convention: every node's contact distance against a plane is half the width of its
// narrowest member (RoomContact), 25 mm for the 50 x 30 tube, so a box whose bottom centre lines sit
// at z = 25 mm just touches the floor (penetration ratio g = 0).
#include <furniture_fem/contact/room_contact.hpp>
#include <furniture_fem/contact/stiff_contact.hpp>
#include <furniture_fem/core/simulation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace ffem_dyn {

using namespace furniture_fem;

inline constexpr double g0 = 9.80665;          // m/s^2
inline constexpr double tube_half_width = 0.025;  // m: L of every node of a 50 x 30 tube frame

inline Section tube() { return Section::hollow_rectangle(0.05, 0.03, 0.002, "50 x 30 x 2"); }
inline Material elastic_steel() {
  Material m = Material::steel();
  m.sigma_y = 1e20;  // no plastic hinges: these tests are about contact and excitation
  return m;
}

// A rectangular box frame: 12 edges of tube, footprint bx (along X) by by (along Y), height h between
// the bottom and top centre lines, footprint centre at `centre` (x, y), bottom centre lines at
// z = 25 mm + centre.z (a box standing on another: centre.z = the lower box's h + 50 mm). With raise > 0 the two bottom edges along X are lifted by `raise` (the posts carry them),
// so the box stands on its two bottom edges along Y only: every floor contact then lies on the lines
// x = +-bx/2, the two rocking pivots.
struct BoxSpec {
  double bx = 0.4, by = 0.3, h = 0.3;
  Vec3 centre = Vec3::Zero();
  double raise = 0;
  double element = 0.05;  // target element length (m), rounded up to even counts per member
};

struct Box {
  int body = -1;
  std::vector<int> bottom;  // nodes whose centre line is at the lowest level (the floor contacts)
  std::vector<int> heel;    // bottom nodes on x = -bx/2 (the left pivot line)
  std::vector<int> toe;     // bottom nodes on x = +bx/2
  std::vector<int> corners; // the 8 corners: bottom 4 then top 4
  double mass = 0;
  Vec3 cog = Vec3::Zero();
  const Model* model = nullptr;  // the model the box is in
};

inline Box add_box(Model& m, const std::string& name, int section, int material, const BoxSpec& s) {
  Box b;
  b.body = m.add_body(name);
  const double z0 = tube_half_width + s.centre.z(), z1 = z0 + s.h, xr = 0.5 * s.bx, yr = 0.5 * s.by;
  const Vec3 c(s.centre.x(), s.centre.y(), 0);
  auto node = [&](double x, double y, double z) { return m.add_node(c + Vec3(x, y, z), b.body); };
  const int b00 = node(-xr, -yr, z0), b10 = node(xr, -yr, z0), b11 = node(xr, yr, z0), b01 = node(-xr, yr, z0);
  const int t00 = node(-xr, -yr, z1), t10 = node(xr, -yr, z1), t11 = node(xr, yr, z1), t01 = node(-xr, yr, z1);
  b.corners = {b00, b10, b11, b01, t00, t10, t11, t01};
  MemberOptions o;
  o.target_length = s.element;
  auto member = [&](const char* nm, int i, int j) { m.add_member(nm, i, j, section, material, o); };
  // Bottom edges along Y (always on the floor).
  member("bottom -x", b00, b01);
  member("bottom +x", b10, b11);
  if (s.raise > 0) {
    const double zr = z0 + s.raise;
    const int r00 = node(-xr, -yr, zr), r10 = node(xr, -yr, zr), r11 = node(xr, yr, zr), r01 = node(-xr, yr, zr);
    member("bottom -y", r00, r10);
    member("bottom +y", r01, r11);
    member("foot 00", b00, r00), member("post 00", r00, t00);
    member("foot 10", b10, r10), member("post 10", r10, t10);
    member("foot 11", b11, r11), member("post 11", r11, t11);
    member("foot 01", b01, r01), member("post 01", r01, t01);
  } else {
    member("bottom -y", b00, b10);
    member("bottom +y", b01, b11);
    member("post 00", b00, t00);
    member("post 10", b10, t10);
    member("post 11", b11, t11);
    member("post 01", b01, t01);
  }
  member("top -y", t00, t10);
  member("top +y", t01, t11);
  member("top -x", t00, t01);
  member("top +x", t10, t11);
  for (int n : m.body(b.body).nodes) {
    const Vec3& X = m.node(n).X;
    if (std::abs(X.z() - z0) < 1e-9) {
      b.bottom.push_back(n);
      if (std::abs(X.x() - (c.x() - xr)) < 1e-9) b.heel.push_back(n);
      if (std::abs(X.x() - (c.x() + xr)) < 1e-9) b.toe.push_back(n);
    }
  }
  b.mass = m.body_mass(b.body);
  b.cog = m.body_centre_of_gravity(b.body);
  b.model = &m;
  return b;
}

// The floor: z = 0, normal +z, unbounded.
inline RigidPlane floor_plane() {
  RigidPlane p;
  p.point = Vec3::Zero();
  p.normal = Vec3::UnitZ();
  return p;
}

// A wall through `point` with inward normal `normal` (the side where items are), unbounded.
inline RigidPlane wall_plane(const Vec3& point, const Vec3& normal) {
  RigidPlane p;
  p.point = point;
  p.normal = normal.normalized();
  p.axis_u = (std::abs(p.normal.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX()).cross(p.normal).normalized();
  p.axis_v = p.normal.cross(p.axis_u);
  p.is_wall = true;
  return p;
}

// The same parameters for floor, walls and other items.
inline BodyContact same_everywhere(const ContactParams& p) {
  BodyContact bc;
  bc.floor = bc.wall = bc.item = p;
  return bc;
}

// Mass-weighted mean of a body's nodal positions and velocities (its centre of mass).
template <class Sim>
Vec3 centre_of_mass(const Sim& sim, int body) {
  double m = 0;
  Vec3 c = Vec3::Zero();
  for (int n : sim.model().body(body).nodes) {
    m += sim.nodal_mass(n);
    c += sim.nodal_mass(n) * sim.position(n);
  }
  return c / m;
}
template <class Sim>
Vec3 centre_of_mass_velocity(const Sim& sim, int body) {
  double m = 0;
  Vec3 v = Vec3::Zero();
  for (int n : sim.model().body(body).nodes) {
    m += sim.nodal_mass(n);
    v += sim.nodal_mass(n) * sim.velocity(n).template head<3>();
  }
  return v / m;
}
template <class Sim>
double lumped_mass(const Sim& sim, int body) {
  double m = 0;
  for (int n : sim.model().body(body).nodes) m += sim.nodal_mass(n);
  return m;
}
template <class Sim>
double max_speed(const Sim& sim, int body) {
  double s = 0;
  for (int n : sim.model().body(body).nodes) s = std::max(s, sim.velocity(n).template head<3>().norm());
  return s;
}
template <class Sim>
double min_z(const Sim& sim, const std::vector<int>& nodes) {
  double z = std::numeric_limits<double>::infinity();
  for (int n : nodes) z = std::min(z, sim.position(n).z());
  return z;
}
template <class Sim>
double max_z(const Sim& sim, const std::vector<int>& nodes) {
  double z = -std::numeric_limits<double>::infinity();
  for (int n : nodes) z = std::max(z, sim.position(n).z());
  return z;
}
template <class Sim>
double mean_z(const Sim& sim, const std::vector<int>& nodes) {
  double z = 0;
  for (int n : nodes) z += sim.position(n).z();
  return z / double(nodes.size());
}

// Contact forces of the current state, evaluated through the simulation's own contact policy, one
// 6-vector per node (forces, then moments). Calling add_forces outside a step is harmless: the
// policy restarts every evaluation from its committed history and only commit() advances it. (A
// stick-slip spring is evaluated one more v dt on from its committed state: a valid evaluation of
// the law, not necessarily the force the last step applied.)
template <class Sim>
Eigen::VectorXd contact_force_vector(Sim& sim) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(6 * sim.model().num_nodes());
  const ContactView view{sim.model(), sim.positions(), sim.velocities(), sim.time(), sim.options().dt};
  sim.contact().add_forces(view, f);
  return f;
}

// The measured numbers of docs/contact/verification_contact.md: printed when FFEM_REPORT is set
//   FFEM_REPORT=1 ./build-dyn/tests/test_contact_dynamics
inline void report(const char* format, ...) {
  if (!std::getenv("FFEM_REPORT")) return;
  std::va_list args;
  va_start(args, format);
  std::vprintf(format, args);
  va_end(args);
  std::printf("\n");
  std::fflush(stdout);
}

// The paper's parameters for an item of mass M (alpha = its weight, q = 1, Dc = 1.2 alpha) with
// friction mu and the regularisation speed v_reg.
inline ContactParams paper_params(double mass, double mu, double v_reg) {
  ContactParams p = ContactParams::paper(mass, mu);
  p.v_reg = v_reg;
  return p;
}

// The paper's Newmark scheme, as the scenes use it.
inline const Newmark paper_newmark = Newmark::paper();

// The paper's law for a box as the scenes set it: their v_reg (1 mm/s) and stick length (10 um), so
// friction sticks.
inline ContactParams paper_stick(const Box& b, double mu) {
  ContactParams p = paper_params(b.mass, mu, 1e-3);
  p.stick_length = 1e-5;
  return p;
}

// The `stiff` rule as the scenes set it (set_stiff_contact), with the scenes' stick length.
inline ContactParams stiff_params(const Box& b, double mu) {
  ContactParams p = paper_stick(b, mu);
  set_stiff_contact(*b.model, b.body, p);
  return p;
}

inline void set_stick_spring(ContactParams& p, double mass, int n, double omega_t, double zeta_t) {
  p.k_t = mass * omega_t * omega_t / n;
  p.c_t = 2 * zeta_t * mass * omega_t / n;
}

// Explicit-damping stability limit of the solver's contact treatment. Contact forces are evaluated
// at the predictor with the velocity v_n + dt a_n and applied over the step (carry-over). A
// dashpot c on a mass M, F = -c (v_n + dt a_n), in Newmark's velocity update gives the one-step
// map of (v, dt a) with trace 1 - (1 + gamma) kappa and determinant -gamma kappa, kappa = c dt / M;
// its eigenvalues stay inside the unit circle while p(-1) = 2 - (1 + 2 gamma) kappa > 0:
//     kappa < 2 / (1 + 2 gamma)          (0.75 for the paper's gamma = 5/6)
// The paper's normal damping, regularised below v_reg, is such a dashpot: Dc g / v_reg per contact,
// 1.2 W / v_reg summed over a resting item (sum alpha g = W, Dc = 1.2 alpha), so the item rests
// without chatter only if
//     v_reg > (1 + 2 gamma) / 2 * 1.2 g dt     (15.7 mm/s at dt = 1 ms, gamma = 5/6)
// and likewise its friction needs v_reg > (1 + 2 gamma) / 2 * mu g dt.
inline double critical_v_reg(double damping_over_weight, double dt, double gamma) {
  return 0.5 * (1 + 2 * gamma) * damping_over_weight * g0 * dt;
}

// A scene of one box frame on the floor (and optional walls), composed with a contact law and an
// integrator; the Model lives on the heap so the Simulation's reference to it stays valid.
template <class Law, class Integrator = Newmark>
struct BlockScene {
  using Sim = Simulation<AsiGaussTimoshenko, Integrator, DirectLdltSolver, RoomContact>;
  std::unique_ptr<Model> model = std::make_unique<Model>();
  Box box;
  std::unique_ptr<Sim> sim;

  BlockScene(const BoxSpec& spec, const std::function<ContactParams(const Box&)>& params, bool rigid,
             const SimulationOptions& options, Integrator integrator, Law law = {},
             std::vector<RigidPlane> planes = {floor_plane()}) {
    const int sec = model->add_section(tube()), mat = model->add_material(elastic_steel());
    box = add_box(*model, "block", sec, mat, spec);
    RoomContact contact(*model, {same_everywhere(params(box))}, std::move(planes), std::move(law));
    sim = std::make_unique<Sim>(*model, integrator, options, std::move(contact));
    if (rigid) sim->set_rigid(box.body);
  }
  Vec3 com() const { return centre_of_mass(*sim, box.body); }
  Vec3 com_velocity() const { return centre_of_mass_velocity(*sim, box.body); }
  double weight() const { return box.mass * g0; }
};

inline SimulationOptions options_dt(double dt) {
  SimulationOptions o;
  o.dt = dt;
  return o;
}

}  // namespace ffem_dyn

// The group's room simulation (Newmark, the direct solver; every law, the law being a run-time kernel):
// its constructor and step are compiled once, in compiled_simulations.cpp, instead of in each unit that
// steps one (docs/performance.md, section 6). `extern` here, nothing there.
#define FFEM_DYNAMICS_SIMULATIONS(EXTERN) \
  FFEM_SIMULATION_RUN_MEMBERS(EXTERN, AsiGaussTimoshenko, Newmark, DirectLdltSolver, RoomContact)
namespace furniture_fem {
FFEM_DYNAMICS_SIMULATIONS(extern)
}  // namespace furniture_fem
