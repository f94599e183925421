// step-5: two contact laws on one scene, and a figure of their difference.
//
// What is new relative to step-4: the contact law is a template parameter. A law is a type,
// ContactLaw<Normal, Damping, Friction>, composed of three small policy classes; the presets differ
// by one part or more (docs/contact/contact.md). One function template runs the scene of step-4 (the rigid
// block under the synthetic earthquake) with any law, so comparing two laws is two instantiations:
//   PaperLaw      = ContactLaw<PowerPenalty, PaperSignDamping, PaperSignFriction>   (paper eqs. 1-4)
//   StickSlipLaw  = ContactLaw<PowerPenalty, PaperSignDamping, StickSlip>
// They share the paper's normal response and differ in the friction only. The paper's friction,
// -mu alpha g v/|v| regularised below v_reg, is a dashpot at low speed, so the block creeps whenever
// the table pushes it at all; the stick-slip friction is a tangential spring held inside the cone
// mu N, so below mu g the block stays put (but for a fraction of a millimetre of spring and tilt). The
// reference is Newmark's rigid-plastic sliding block (step-4). The figure, written with plot.hpp's
// LinePlot, stacks the table acceleration, the slips and their difference.
#include <furniture_fem/excitation/excitation.hpp>
#include <furniture_fem/figures/plot.hpp>
#include <furniture_fem/contact/room_contact.hpp>
#include <furniture_fem/core/simulation.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace furniture_fem;

namespace {

constexpr double g = 9.80665, mu = 0.3, dt = 2e-4, t_end = 7.0;

// The block of step-4: a 0.4 x 0.3 x 0.3 m box frame of 50 x 30 x 2 mm tube at first touch.
struct Block {
  Model model;
  int body = 0;
  double mass = 0;
  int contacts = 0;
  Block() {
    body = model.add_body("block");
    const int tube = model.add_section(Section::hollow_rectangle(0.05, 0.03, 0.002, "50 x 30 x 2"));
    Material steel;
    steel.sigma_y = 1e20;
    const int mat = model.add_material(steel);
    int c[8];
    for (int k = 0; k < 8; ++k)
      c[k] = model.add_node({(k & 1) ? 0.2 : -0.2, (k & 2) ? 0.15 : -0.15, (k & 4) ? 0.325 : 0.025}, body);
    for (int a = 0; a < 8; ++a)
      for (int bit : {1, 2, 4})
        if (!(a & bit)) model.add_member("edge", c[a], c[a | bit], tube, mat);
    for (int n = 0; n < model.num_nodes(); ++n) contacts += std::abs(model.node(n).X.z() - 0.025) < 1e-9;
    mass = model.body_mass(body);
  }
};

// One set of parameters serves both laws: each law reads the fields its parts use (alpha, Dc, q,
// v_reg for the normal parts; mu and v_reg for the paper's friction; mu, k_t, c_t for the stick-slip
// friction). The tangential spring gives the block a 48 Hz stick mode (omega_t = 300 rad/s), 70%
// damped: n k_t = M omega_t^2, n c_t = 2 zeta M omega_t.
ContactParams parameters(const Block& b) {
  ContactParams p = ContactParams::paper(b.mass, mu);  // alpha = W, q = 1, Dc = 1.2 alpha
  p.v_reg = 12e-3;  // above the explicit-damping limit 3.1 mm/s of the rigid block at dt 0.2 ms (step-4)
  const double omega_t = 300, zeta_t = 0.7;
  p.k_t = b.mass * omega_t * omega_t / b.contacts;
  p.c_t = 2 * zeta_t * b.mass * omega_t / b.contacts;
  return p;
}

struct History {
  std::vector<double> t, slip;  // s, mm (block on the table, along X)
};

// The scene, for any law: the only line that names the law is the solver's type.
template <class Law>
History run(const Block& block, const TableMotion& motion, Law law = {}) {
  BodyContact bc;
  bc.floor = bc.wall = bc.item = parameters(block);
  RigidPlane floor;  // z = 0, normal +z
  RoomContact contact(block.model, {bc}, {floor}, law);
  SimulationOptions o;
  o.dt = dt;
  Simulation<AsiGaussTimoshenko, Newmark, DirectLdltSolver, RoomContact> sim(block.model, Newmark::paper(), o,
                                                                                  std::move(contact));
  sim.set_rigid(block.body);
  sim.run_until(0.5);  // settle
  const double ts = sim.time();
  auto x = [&] {
    double m = 0, s = 0;
    for (int n = 0; n < block.model.num_nodes(); ++n) m += sim.nodal_mass(n), s += sim.nodal_mass(n) * sim.position(n).x();
    return s / m;
  };
  const double x0 = x();
  sim.set_table_acceleration([&](double t) { return motion(t - ts); });
  History h{{0.0}, {0.0}};
  int step = 0;
  sim.run_until(ts + t_end, [&](const auto& s, const StepInfo&) {
    if (++step % 50) return;  // every 10 ms
    h.t.push_back(s.time() - ts);
    h.slip.push_back(1e3 * (x() - x0));
  });
  return h;
}

// Newmark's (1965) sliding block on the same record, sampled like the histories (10 us steps).
History sliding_block(const TableMotion& motion) {
  History h{{0.0}, {0.0}};
  const double step = 1e-5;
  double v = 0, x = 0;
  const long n = std::lround(t_end / step), every = std::lround(0.01 / step);
  for (long i = 1; i <= n; ++i) {
    const double a = motion(i * step).x();
    if (v == 0 && std::abs(a) > mu * g) v = -(a - std::copysign(mu * g, a)) * step;
    else if (v != 0) {
      const double v1 = v + (-a - std::copysign(mu * g, v)) * step;
      v = (v1 * v < 0) ? 0.0 : v1;
    }
    x += v * step;
    if (i % every == 0) h.t.push_back(i * step), h.slip.push_back(1e3 * x);
  }
  return h;
}

}  // namespace

int main() {
  const Block block;
  SyntheticOptions so;  // the record of step-4: PGA 6 m/s^2 = 2 mu g
  so.seed = 4;
  so.duration = 6.0;
  so.pga = 6.0;
  so.predominant_period = 0.5;
  const TableMotion motion = TableMotion::one_d(synthetic_motion(so));
  std::printf("Rigid block %.3f kg on %d contacts, mu = %.1f, synthetic record PGA %.1f m/s^2, dt = %.1f ms\n", block.mass,
              block.contacts, mu, so.pga, dt * 1e3);

  // Two instantiations of the same scene. Runtime options of a law sit on its parts, e.g. which
  // normal force the friction cone uses: law.friction_part().normal = FrictionNormal::total.
  const History paper = run<PaperLaw>(block, motion);
  const History stick = run<StickSlipLaw>(block, motion);
  const History ref = sliding_block(motion);

  // The numbers: the slip at a few times and at the end, and where the laws differ most.
  std::printf("\n%8s %14s %12s %14s %14s %12s\n", "t (s)", "a_table (m/s2)", "PaperLaw", "StickSlipLaw", "sliding block",
              "difference");
  std::printf("%8s %14s %12s %14s %14s %12s\n", "", "", "(mm)", "(mm)", "(mm)", "(mm)");
  std::vector<double> a_table, diff;
  double worst = 0, worst_t = 0;
  for (size_t i = 0; i < paper.t.size(); ++i) {
    a_table.push_back(motion(paper.t[i]).x());
    diff.push_back(paper.slip[i] - stick.slip[i]);
    if (std::abs(diff.back()) > std::abs(worst)) worst = diff.back(), worst_t = paper.t[i];
    if (i % 50 == 0 || i + 1 == paper.t.size())
      std::printf("%8.2f %14.3f %12.2f %14.2f %14.2f %12.2f\n", paper.t[i], a_table.back(), paper.slip[i], stick.slip[i],
                  ref.slip[i], diff.back());
  }
  std::printf("\nFinal slip: PaperLaw %.2f mm, StickSlipLaw %.2f mm, sliding block %.2f mm\n", paper.slip.back(),
              stick.slip.back(), ref.slip.back());
  std::printf("Largest difference PaperLaw - StickSlipLaw: %.2f mm at t = %.2f s\n", worst, worst_t);
  // Until the table first exceeds mu g the sliding block is at rest; how far did each law move?
  double t_first = 0;
  while (std::abs(motion(t_first).x()) <= mu * g) t_first += 1e-4;
  double creep_paper = 0, creep_stick = 0;
  for (size_t i = 0; i < paper.t.size() && paper.t[i] < t_first; ++i) {
    creep_paper = std::max(creep_paper, std::abs(paper.slip[i]));
    creep_stick = std::max(creep_stick, std::abs(stick.slip[i]));
  }
  std::printf("Before the table first exceeds mu g (t = %.3f s): PaperLaw moved up to %.2f mm, StickSlipLaw %.3f mm\n",
              t_first, creep_paper, creep_stick);

  // The figure: three panels sharing the time axis. add() draws a solid series in the panel's next
  // colour, add_reference() a dashed black one (the sliding block, and the +-mu g levels).
  LinePlot plot("Rigid block on a shaking floor: PaperLaw against StickSlipLaw");
  plot.panels(3).xlabel("time (s)");
  plot.style().legend = LegendPos::top_left;  // the first second is quiet in every panel
  plot.ylabel("table acc. (m/s^2)", 0).ylabel("slip (mm)", 1).ylabel("difference (mm)", 2);
  plot.add(paper.t, a_table, "table acceleration", 0);
  plot.add_reference({0, t_end}, {mu * g, mu * g}, "+-mu g", 0);
  plot.add_reference({0, t_end}, {-mu * g, -mu * g}, "", 0);
  plot.add(paper.t, paper.slip, "PaperLaw", 1);
  plot.add(stick.t, stick.slip, "StickSlipLaw", 1);
  plot.add_reference(ref.t, ref.slip, "Newmark sliding block", 1);
  plot.add(paper.t, diff, "PaperLaw - StickSlipLaw", 2);
  const std::string png = "step-5-contact-laws.png";
  plot.save_png(png, 1100, 900);
  std::printf("\nWrote %s\n", png.c_str());
  return 0;
}
