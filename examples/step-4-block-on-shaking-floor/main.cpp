// step-4: a steel block on the floor of a shake table: contact, the table frame and rigid bodies.
//
// What is new relative to step-3: the structure is no longer fixed. It stands on the floor, held by
// the paper's penalty contact (RoomContact with PaperLaw), and the floor moves: the table's
// acceleration drives the scene (set_table_acceleration). Three results are compared with closed
// forms:
//   1. at rest, the contacts carry the weight: sum over the bottom nodes of alpha g_i = M g, so with
//      n contacts at equal penetration g = M g / (n alpha);
//   2. a rectangular acceleration pulse (A g for t0 seconds) makes the block slide and stop again
//      after the slip V^2 / (2 mu g) (1 - mu / A), V = A g t0;
//   3. under a synthetic earthquake it slides whenever the table's acceleration exceeds mu g, and
//      only then.
// The block is solved both as a finite-element body and as a rigid body (set_rigid), which has the
// same nodes, masses and contact geometry but six degrees of freedom.
#include <furniture_fem/excitation/excitation.hpp>
#include <furniture_fem/contact/room_contact.hpp>
#include <furniture_fem/core/simulation.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace furniture_fem;

namespace {

constexpr double g = 9.80665;

// The model: a 0.4 x 0.3 x 0.3 m box frame (the twelve edges) of the paper's 50 x 30 x 2 mm tube.
// Contact with a plane is judged at the nodes: a node touches the floor when its centre line is
// within L of it, L being half the width of its narrowest member (25 mm here). The bottom centre
// lines are placed at z = L, so the block starts exactly at first touch.
struct Block {
  Model model;
  int body = 0;
  std::vector<int> bottom;  // the nodes on the floor
  double mass = 0;
  Block() {
    body = model.add_body("block");
    const int tube = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "50 x 30 x 2"));
    Material steel;
    steel.sigma_y = 1e20;  // this step is about contact, not plasticity
    const int mat = model.add_material(steel);
    const double L = 0.025, x = 0.2, y = 0.15, h = 0.3;
    int c[8];
    for (int k = 0; k < 8; ++k)
      c[k] = model.add_node({(k & 1) ? x : -x, (k & 2) ? y : -y, (k & 4) ? L + h : L}, body);
    // The twelve edges: pairs of corners that differ in one coordinate (one bit of k).
    for (int a = 0; a < 8; ++a)
      for (int bit : {1, 2, 4})
        if (!(a & bit)) model.add_member("edge", c[a], c[a | bit], tube, mat);  // 50 mm elements, in pairs
    for (int n = 0; n < model.num_nodes(); ++n)
      if (std::abs(model.node(n).X.z() - L) < 1e-9) bottom.push_back(n);
    mass = model.body_mass(body);
  }
};

// The contact parameters. ContactParams::paper applies the paper's rules (Table 4): alpha = the
// item's weight (given in kgf, stored in N), q = 1, Dc = 1.2 alpha; mu is the dynamic friction.
// v_reg is where the law's v/|v| is smoothed. The solver applies contact forces explicitly (from
// each step's predictor), and below v_reg the paper's normal damping is a dashpot Dc g / v_reg per
// contact: 1.2 W / v_reg on the whole block. An explicit dashpot c on a mass m is stable only while
// c dt / m < 2 / (1 + 2 gamma) (gamma = 5/6 for the paper's Newmark), so
//     rigid block:  v_reg > (1 + 2 gamma)/2 * 1.2 g dt                = 3.1 mm/s at dt = 0.2 ms;
//     FE block:     the same per node, with the node's load over its mass in place of g: a bottom node
//                   carries W/28 = 3.3 N on 0.12 kg (2.9 g), so v_reg > 9 mm/s at dt = 0.2 ms.
// Below that the block chatters and never settles (docs/contact/verification_contact.md). A larger v_reg
// smooths the friction more: the block passes more slowly through |v| < v_reg when it starts to
// slide, which lengthens the slip by about mu v_reg / A per second of sliding. 12 mm/s here.
ContactParams contact_parameters(const Block& b, double mu) {
  ContactParams p = ContactParams::paper(b.mass, mu);  // alpha = M g
  p.v_reg = 12e-3;
  return p;
}

// The solver type: ASI-Gauss elements, the paper's Newmark, a sparse direct solver, and the room's
// contact with the paper's law.
using Sim = Simulation<AsiGaussTimoshenko, Newmark, DirectLdltSolver, RoomContact>;

// RoomContact takes one BodyContact per body (floor, wall and item-item parameters) and the rigid
// planes of the room: here only the floor, the plane z = 0 with normal +z.
RoomContact floor_contact(const Block& b, double mu) {
  BodyContact bc;
  bc.floor = bc.wall = bc.item = contact_parameters(b, mu);
  RigidPlane floor;
  floor.point = Vec3::Zero();
  floor.normal = Vec3::UnitZ();
  return RoomContact(b.model, {bc}, {floor}, PaperLaw{});
}

SimulationOptions options() {
  SimulationOptions o;
  o.dt = 2e-4;  // s
  return o;
}

Vec3 centre_of_mass(const Sim& sim, const Model& model) {
  Vec3 c = Vec3::Zero();
  double m = 0;
  for (int n = 0; n < model.num_nodes(); ++n) {
    c += sim.nodal_mass(n) * sim.position(n);
    m += sim.nodal_mass(n);
  }
  return c / m;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main() {
  const Block block;
  const double mu = 0.3, W = block.mass * g;
  const int n = static_cast<int>(block.bottom.size());
  std::printf("Block 0.4 x 0.3 x 0.3 m, %d nodes, M = %.3f kg, %d nodes on the floor, L = 25 mm\n", block.model.num_nodes(),
              block.mass, n);
  std::printf("Paper law: alpha = W = %.2f N per contact, Dc = 1.2 alpha, mu = %.1f, v_reg = 12 mm/s, dt = 0.2 ms\n\n", W, mu);

  // 1. Settling. Released at first touch, the block sinks until the contacts carry its weight.
  // The paper's normal damping has a constant magnitude Dc g (it acts like Coulomb friction in the
  // normal direction), so the last part of the way is a creep at about v_reg, time constant
  // 1.2 g L / v_reg = 0.09 s.
  std::printf("1. Resting on the floor for 1 s: mean penetration ratio g = 1 - l/L of the bottom nodes\n");
  for (const bool rigid : {false, true}) {
    Sim sim(block.model, Newmark::paper(), options(), floor_contact(block, mu));
    if (rigid) sim.set_rigid(block.body);
    const auto t0 = std::chrono::steady_clock::now();
    sim.run_until(1.0);
    double gm = 0, gmin = 1, gmax = 0, vmax = 0;
    for (int k : block.bottom) {
      const double gk = 1 - sim.position(k).z() / 0.025;
      gm += gk / n, gmin = std::min(gmin, gk), gmax = std::max(gmax, gk);
    }
    for (int k = 0; k < block.model.num_nodes(); ++k) vmax = std::max(vmax, sim.velocity(k).head<3>().norm());
    std::printf("   %-13s g = %.8f (from %.8f to %.8f), closed form W/(n alpha) = 1/n = %.8f; max speed %.1e m/s  [%.2f s]\n",
                rigid ? "rigid body:" : "finite elem.:", gm, gmin, gmax, 1.0 / n, vmax, seconds_since(t0));
  }

  // 2. A rectangular pulse. The simulation works in the table frame: every mass gets -m a_table(t)
  // and displacements are relative to the table, so the slip is the block's displacement.
  const double A = 0.5, t_pulse = 0.3, V = A * g * t_pulse;
  const double slip_closed = V * V / (2 * mu * g) * (1 - mu / A);
  std::printf("\n2. Table pulse %.1f g for %.1f s (V = %.3f m/s): slip closed form V^2/(2 mu g)(1 - mu/A) = %.4f m\n", A,
              t_pulse, V, slip_closed);
  for (const bool rigid : {false, true}) {
    Sim sim(block.model, Newmark::paper(), options(), floor_contact(block, mu));
    if (rigid) sim.set_rigid(block.body);
    sim.run_until(0.5);  // settle first
    const double ts = sim.time(), x0 = centre_of_mass(sim, block.model).x();
    sim.set_table_acceleration(
        [=](double t) { return Vec3(t > ts + 1e-9 && t <= ts + t_pulse + 1e-9 ? A * g : 0.0, 0, 0); });
    const auto t0 = std::chrono::steady_clock::now();
    double v_peak = 0;
    sim.run_until(ts + 1.5, [&](const Sim& s, const StepInfo&) {
      v_peak = std::max(v_peak, std::abs(s.velocity(block.bottom[0]).x()));
    });
    const double slip = x0 - centre_of_mass(sim, block.model).x();
    std::printf("   %-13s slip %.4f m (%+.1f%% against the closed form), peak sliding speed %.3f m/s (closed form "
                "(A - mu) g t0 = %.3f)  [%.2f s]\n",
                rigid ? "rigid body:" : "finite elem.:", slip, 100 * (slip / slip_closed - 1), v_peak, (A - mu) * g * t_pulse,
                seconds_since(t0));
  }
  std::printf("   (Two effects lengthen the slip. The regularisation: while |v| < v_reg at the start and the end of the\n"
              "    slide the friction is below mu W (at most mu v_reg / A x 0.5 s = 3.6 mm). And the paper's friction acts\n"
              "    on the penalty part alpha g of the normal force: while the tilt the pulse gave the block settles, the\n"
              "    constant-magnitude damping carries about 1%% of the weight, and the slip grows 2.5 times as fast as\n"
              "    the friction falls. step-5 compares laws.)\n");

  // 3. An earthquake. excitation.hpp makes seeded synthetic ground motions (Kanai-Tajimi filtered
  // noise under an envelope, corrected to end at rest); TableMotion bundles the components and can
  // be called like set_table_acceleration's function. The reference is Newmark's (1965) sliding
  // block: a rigid block on a rigid floor with exact Coulomb friction, integrated here with 10 us
  // steps. It sticks while |a_table| <= mu g; sliding, its velocity on the table obeys
  // dv/dt = -a_table - mu g sign(v) until v returns to zero.
  SyntheticOptions so;
  so.seed = 4;
  so.duration = 6.0;
  so.pga = 6.0;  // m/s^2: 2 mu g
  so.predominant_period = 0.5;
  const TableMotion motion = TableMotion::one_d(synthetic_motion(so));
  const double T = so.duration + 1.0, h = 1e-5;
  std::vector<double> ref_slip;  // every 0.5 s
  {
    double v = 0, x = 0;
    const long steps = std::lround(T / h);
    for (long i = 1; i <= steps; ++i) {
      const double a = motion(i * h).x();
      if (v == 0 && std::abs(a) > mu * g) v = -(a - std::copysign(mu * g, a)) * h;  // starts to slide
      else if (v != 0) {
        const double v1 = v + (-a - std::copysign(mu * g, v)) * h;
        v = (v1 * v < 0) ? 0.0 : v1;  // friction stops it; it cannot reverse it
      }
      x += v * h;
      if (i % std::lround(0.5 / h) == 0) ref_slip.push_back(x);
    }
  }
  std::printf("\n3. Synthetic motion, PGA %.1f m/s^2 = %.2f mu g, %.0f s, rigid block, against Newmark's sliding block\n",
              so.pga, so.pga / (mu * g), so.duration);
  Sim sim(block.model, Newmark::paper(), options(), floor_contact(block, mu));
  sim.set_rigid(block.body);
  sim.run_until(0.5);
  const double ts = sim.time(), x0 = centre_of_mass(sim, block.model).x();
  sim.set_table_acceleration([&](double t) { return motion(t - ts); });
  std::printf("   %6s %14s %12s %16s\n", "t (s)", "a_table (m/s2)", "slip (mm)", "sliding block (mm)");
  int step = 0;
  const auto t0 = std::chrono::steady_clock::now();
  sim.run_until(ts + T, [&](const Sim& s, const StepInfo&) {
    if (++step % 2500 == 0)
      std::printf("   %6.2f %14.3f %12.2f %16.2f\n", s.time() - ts, motion(s.time() - ts).x(),
                  1e3 * (centre_of_mass(s, block.model).x() - x0), 1e3 * ref_slip.at(step / 2500 - 1));
  });
  std::printf("   [%.2f s]\n", seconds_since(t0));
  std::printf("   (Between 0.5 and 1.5 s the table stays below mu g: the sliding block does not move, the paper's\n"
              "    regularised friction creeps at v = F v_reg / (mu W). step-5 puts a stick-slip friction beside it.)\n");
  return 0;
}
