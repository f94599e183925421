// Hard cases with impacts: the separated cabinets toppling together under a strong pulse, and a tall
// cabinet falling onto the desk. Both end with bodies striking the floor or each other at ~1-3 m/s,
// where the carried-over (explicit) contact forces lose energy at the impact: the ledger's
// imbalance is that loss, bounded here as measured and shown to shrink with dt.
// Short version (default): coarse meshes. FFEM_FULL_STABILITY=1: full fidelity.
#include "stability_support.hpp"

using namespace stability;

namespace toppling_tests {  // this file's own names (its group compiles files in batches)

namespace {

// The separated cabinets (lower and upper body, stacked) alone on the floor, front towards -X, hit
// by one half-sine table pulse of `peak` m/s^2 along X lasting 0.3 s.
Outcome stack_under_pulse(Fidelity fidelity, double dt, double duration, bool iterate = false) {
  SceneSpec s = open_floor("stacked cabinets, pulse", dt, duration);
  s.items.push_back({"stack", ItemKind::separated_cabinets, 0.0, 0.0, -90.0, fidelity, {}});
  s.integrator.iterate_to_equilibrium = iterate;
  Scene scene(s, 0, 1);
  constexpr double peak = 8.0, width = 0.3;
  scene.sim->set_table_acceleration(
      [](double t) { return Vec3(t < width ? peak * std::sin(std::numbers::pi * t / width) : 0.0, 0, 0); });
  return run(scene, s, duration);
}

}  // namespace

TEST_CASE("stability: stacked cabinets topple together under a strong pulse", "[stability][toppling]") {
  const bool full = full_mode();
  // Measured (Release, g++ 12, dt = 1 ms, carry-over with the finite-rotation update): coarse -0.089
  // at the end (the largest), full fidelity -0.169 (before the update: -0.242 and -0.393, the
  // rotation itself was being damped). Almost all of it is lost in the ~0.05 s when the upper
  // cabinet lands on the floor. The bounds were set before the update and are kept (they now leave
  // a margin of ~3-4); the check that matters for
  // stability is that the sign is a loss (no energy created) and that it shrinks with dt (below).
  const double bound = full ? 0.5 : 0.35;
  const Outcome o = stack_under_pulse(full ? Fidelity::full : Fidelity::coarse, 1e-3, full ? 3.0 : 2.5);
  report("stacked cabinets toppling (8 m/s^2 pulse)", o, "< " + num(bound),
         std::string(full ? "full" : "coarse") + " mesh, 1 ms; tilts " + num(o.item("stack/lower").tilt_deg) + " / " +
             num(o.item("stack/upper").tilt_deg) + " deg");
  require_trusted(o, bound);
  CHECK(o.imbalance < 0);  // lost, never made
  CHECK(o.min_z > 0.0);    // nothing ends below the floor
  // Both cabinets go over (the pulse tips the pair towards -X; the upper one lands beyond the lower).
  CHECK(o.item("stack/lower").tilt_deg > 60);
  CHECK(o.item("stack/upper").tilt_deg > 60);

  // The loss at the impact is a time-discretisation error of the explicit contact, not a leak:
  // at dt = 0.25 ms it falls to 0.022 (coarse; measured), a factor ~9 for a factor 4 in dt.
  const Outcome fine = stack_under_pulse(Fidelity::coarse, 2.5e-4, 2.5);
  report("stacked cabinets toppling, dt = 0.25 ms", fine, "< 0.05", "coarse mesh: convergence of the impact loss");
  require_trusted(fine, 0.05);
  CHECK(fine.item("stack/upper").tilt_deg > 60);

  if (full) {
    // Newton iterations to equilibrium at dt = 1 ms close the ledger to ~1 % (measured 0.0083 at the
    // end, 0.040 at worst, coarse) at ten times the cost.
    const Outcome it = stack_under_pulse(Fidelity::coarse, 1e-3, 2.5, true);
    report("stacked cabinets toppling, iterate to equilibrium", it, "< 0.08", "coarse mesh, 1 ms");
    require_trusted(it, 0.08);
  }
}

namespace {

// A tall cabinet (front towards -X) 0.2 m behind the desk's back edge, given a forward tipping
// velocity of `omega` rad/s about its front bottom edge: it falls onto the desk top's back edge.
struct FallResult {
  Outcome outcome;
  double gap = 0;
};
FallResult cabinet_onto_desk(Fidelity fidelity, double dt, double duration, double omega) {
  SceneSpec s = open_floor("cabinet falling onto the desk", dt, duration);
  const double cabinet_x = 0.5, depth = paper_item(PaperItem::tall_cabinet).D;
  const double front = cabinet_x - 0.5 * depth, gap = 0.2;
  const double desk_x = front - gap - 0.5 * paper_item(PaperItem::desk).D;  // desk depth along X (yaw -90)
  s.items.push_back({"tall_cabinet", ItemKind::tall_cabinet, cabinet_x, 0.0, -90.0, fidelity, {}});
  s.items.push_back({"desk", ItemKind::desk, desk_x, 0.0, -90.0, fidelity, {}});
  validate(s);
  Scene scene(s, 0, 1);
  // Rotation about +Y with angular velocity -omega tips the top towards -X, about the front edge.
  scene.sim->set_body_velocity(scene.items[0].body, Vec3::Zero(), Vec3(0, -omega, 0), Vec3(front, 0, 0));
  return {run(scene, s, duration), gap};
}

}  // namespace

TEST_CASE("stability: a tall cabinet falls onto the desk", "[stability][toppling]") {
  const bool full = full_mode();
  // 1 rad/s is about twice what tips the cabinet over its front edge (the centre of gravity rises
  // 17 mm: 0.53 rad/s).
  const FallResult r = cabinet_onto_desk(full ? Fidelity::full : Fidelity::coarse, 1e-3, full ? 3.0 : 2.5, 1.0);
  const Outcome& o = r.outcome;
  // Measured: coarse -0.051 at the end and at worst, full fidelity -0.103 (docs/performance.md);
  // lost at the strike on the desk's edge and the landing. Bound: x2 margin.
  const double bound = full ? 0.2 : 0.1;
  report("tall cabinet falling onto the desk", o, "< " + num(bound),
         std::string(full ? "full" : "coarse") + " mesh, 1 ms, 1 rad/s initial tip; cabinet tilt " +
             num(o.item("tall_cabinet").tilt_deg) + " deg, desk pushed " + num(o.item("desk").shift.head<2>().norm()) +
             " m, peak cabinet-desk force " + num(o.max_pair_force) + " N");
  require_trusted(o, bound);
  CHECK(o.imbalance < 0);
  CHECK(o.min_z > 0.0);
  INFO("largest cabinet-desk contact force " << o.max_pair_force << " N; cabinet tilt "
                                             << o.item("tall_cabinet").tilt_deg << " deg, desk shift "
                                             << o.item("desk").shift.transpose());
  // It struck the desk (a contact force between the two bodies of more than its weight) and went
  // over (more than the 16 deg at which its face meets the desk's edge).
  CHECK(o.max_pair_force > 43.6 * 9.81);
  CHECK(o.item("tall_cabinet").max_tilt_deg > 16);
  // The desk stays upright.
  CHECK(o.item("desk").tilt_deg < 20);
}

}  // namespace toppling_tests
