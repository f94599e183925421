// The `stiff` law (contact/stiff_contact.hpp) against rigid-block mechanics, at rigid fidelity and as a
// flexible frame (FE), over two block shapes:
//  1. a rectangular pulse overturns a block exactly at the threshold of an independent, nonlinear
//     1-DOF rocking integration (Housner's problem, first excursion): 1 % rigid, 2 % FE;
//  2. free rocking: time to the first impact within 0.1 % of the same integration (dt 0.25 ms); the restitution
//     reported against Housner's 1 - 2 m R^2 sin^2(alpha) / I_O (1 - 1.5 sin^2(alpha) for a solid block);
//  3. a block dropped at 5 m/s onto the floor and thrown at 5 m/s against a wall: no tunnelling, at most
//     5 mm in at dt 1 ms; at 0.1 ms 1 mm (rigid) and 1.5 mm (FE);
//  4. overturned by pulses past the threshold, a rigid block lands on its side with no net positive work
//     of the contact forces as the integrator applied them, also when the pulse changes in its ninth digit;
//  5. the ledger's contact work as applied is what the items got: for a block dropped flat (no
//     rotation) it equals the kinetic energy's change less gravity's work, computed from the centre of
//     mass's velocity outside the ledger.
// Measured numbers: docs/contact/verification_contact.md (FFEM_REPORT=1 prints them).
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "dynamics_scenes.hpp"

using namespace ffem_dyn;
using Catch::Matchers::WithinAbs;

namespace stiff_law_tests {  // this file's own names (its group compiles files in batches)

namespace {


// Blocks standing on their two bottom edges along Y only (raise: the X edges are lifted), so they
// rock about clean pivot lines x = +-bx/2.
const BoxSpec medium_block{0.4, 0.3, 0.8, Vec3::Zero(), 0.1, 0.05};
const BoxSpec tall_block{0.45, 0.4, 1.2, Vec3::Zero(), 0.1, 0.1};

ContactParams stiff(const Box& b, double mu) { return stiff_params(b, mu); }

// A rigid block rocking on its toe (the pivot line x = +bx/2 at the nodes' centre line), theta its
// lean towards the toe, under a table acceleration a(t) along -X (the inertial force pushes towards
// the toe): I_O theta'' = m R (a cos(alpha - theta) - g sin(alpha - theta)), theta >= 0.
struct Rocker {
  double m, I_O, R, alpha;
  Vec3 pivot;

  static Rocker of(const Model& model, const Box& box, double bx) {
    const Vec3 pivot(0.5 * bx, 0, tube_half_width);
    const Vec3 r = box.cog - pivot;
    const Mat3 I = model.body_inertia(box.body, pivot);
    return {box.mass, I(1, 1), std::hypot(r.x(), r.z()), std::atan2(-r.x(), r.z()), pivot};
  }
  double p() const { return std::sqrt(m * g0 * R / I_O); }
  double accel(double theta, double a) const {
    return m * R / I_O * (a * std::cos(alpha - theta) - g0 * std::sin(alpha - theta));
  }

  struct Excursion {
    bool overturned;
    double t_return;  // when theta comes back to 0 (the first impact), if it does
  };
  // RK4 from (theta0, omega0) at t = 0 under a(t); stops at the first impact or once past alpha + 0.2.
  template <class A>
  Excursion excursion(double omega0, A&& a, double t_end, double h = 2e-6) const {
    double th = 0, om = omega0, t = 0;
    while (t < t_end) {
      if (th <= 0 && om <= 0 && accel(0, a(t)) <= 0 && t > 0) return {false, t};
      const double k1 = om, l1 = accel(th, a(t));
      const double k2 = om + 0.5 * h * l1, l2 = accel(th + 0.5 * h * k1, a(t + 0.5 * h));
      const double k3 = om + 0.5 * h * l2, l3 = accel(th + 0.5 * h * k2, a(t + 0.5 * h));
      const double k4 = om + h * l3, l4 = accel(th + h * k3, a(t + h));
      const double th1 = std::max(0.0, th + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
      const double om1 = om + h / 6 * (l1 + 2 * l2 + 2 * l3 + l4);
      if (th > 0 && th1 <= 0) return {false, t + h * th / (th - (th + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)))};
      th = th1, om = th1 > 0 ? om1 : std::max(0.0, om1), t += h;
      if (th > alpha + 0.2) return {true, -1};
    }
    return {false, -1};
  }
  // The smallest rectangular-pulse amplitude (duration td) that overturns it, by bisection.
  double pulse_threshold(double td) const {
    double lo = g0 * std::tan(alpha), hi = 20 * lo;
    for (int i = 0; i < 40; ++i) {
      const double A = 0.5 * (lo + hi);
      (excursion(0.0, [&](double t) { return t < td ? A : 0.0; }, td + 10.0, 2e-5).overturned ? hi : lo) = A;
    }
    return 0.5 * (lo + hi);
  }
};

}  // namespace

TEST_CASE("a rectangular pulse overturns a block at the rigid-block threshold, stiff law",
          "[contact_dynamics][rocking][stiff]") {
  // Duration 1/p (p the rocking frequency parameter): the threshold is about 1.6 g tan(alpha), far
  // from the static one. Housner's small-angle form 1/(1 - exp(-p td)) is reported beside it.
  for (const auto& [spec, label] : {std::pair{medium_block, "medium"}, std::pair{tall_block, "tall"}})
    for (const bool rigid : {true, false}) {
      const double margin = rigid ? 0.01 : 0.02;
      for (const double level : {1 - margin, 1 + margin}) {
        const double mu = 2.0;  // no sliding: it rocks
        BlockScene<SpringDashpotLaw> s(spec, [&](const Box& b) { return stiff(b, mu); }, rigid, options_dt(1e-3),
                                       paper_newmark);
        const Rocker rock = Rocker::of(*s.model, s.box, spec.bx);
        const double td = 1 / rock.p(), threshold = rock.pulse_threshold(td);
        const double housner = g0 * rock.alpha / (1 - std::exp(-rock.p() * td));
        s.sim->run_until(0.3);
        const double t0 = s.sim->time(), A = level * threshold;
        s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 && t <= t0 + td ? -A : 0.0, 0, 0); });
        double beyond = -1e300;  // how far the centre of gravity passed the toe (> 0: past the tipping point)
        s.sim->run_until(t0 + td + 3.0, [&](const auto& sim, const StepInfo&) {
          beyond = std::max(beyond, centre_of_mass(sim, s.box.body).x() - rock.pivot.x());
        });
        report("S1 pulse %.2f x threshold %.4f g (tan alpha %.4f, Housner small-angle %.4f g), td %.3f s, %s block, %s: "
               "centre of gravity past the toe by %.3f m",
               level, threshold / g0, std::tan(rock.alpha), housner / g0, td, label, rigid ? "rigid" : "FE", beyond);
        INFO(label << (rigid ? " rigid" : " FE") << " level " << level);
        if (level > 1)
          CHECK(beyond > 0.1);
        else
          CHECK(beyond < 0);
      }
    }
}

TEST_CASE("free rocking: time to the first impact and Housner's restitution, stiff law", "[contact_dynamics][rocking][stiff]") {
  // Started at rest on the floor with the angular velocity that lifts it to half its slenderness
  // angle, about the toe: it rises, falls back and strikes with its heel. The impact time is where the
  // heel's mean height crosses its start (interpolated between steps). The angular velocity is the
  // rigid-body one, the angular momentum about the corner it turns on over I_O (a frame's own
  // vibration does not enter); after the impact it is taken 10 ms later, the spin-down by gravity
  // since the impact added back. The paper's Newmark (gamma 5/6) is first order: 0.2 % early or late
  // at dt 1 ms, halved at 0.5 ms (measured), so the 0.1 % is asserted at dt 0.25 ms.
  for (const double dt : {1e-3, 2.5e-4})
    for (const auto& [spec, label] : {std::pair{medium_block, "medium"}, std::pair{tall_block, "tall"}})
      for (const bool rigid : {true, false}) {
        BlockScene<SpringDashpotLaw> s(spec, [&](const Box& b) { return stiff(b, 2.0); }, rigid, options_dt(dt),
                                       paper_newmark);
        const Rocker rock = Rocker::of(*s.model, s.box, spec.bx);
        const Vec3 heel_pivot(-rock.pivot.x(), 0, rock.pivot.z());
        const double lift = 0.5 * rock.alpha;
        const double omega0 =
            std::sqrt(2 * rock.m * g0 * rock.R * (std::cos(rock.alpha - lift) - std::cos(rock.alpha)) / rock.I_O);
        const double t_exact = rock.excursion(omega0, [](double) { return 0.0; }, 10.0).t_return;
        const double e_housner = 1 - 2 * rock.m * rock.R * rock.R * std::pow(std::sin(rock.alpha), 2) / rock.I_O;
        s.sim->set_body_velocity(s.box.body, Vec3::Zero(), Vec3(0, omega0, 0), rock.pivot);

        const double z0 = tube_half_width, tau = 0.01;
        const double spin_down = rock.m * g0 * rock.R * std::sin(rock.alpha) / rock.I_O;
        double t_hit = -1, omega_in = 0, omega_out = 0, prev_rise = 0, prev_t = 0;
        s.sim->run_until(t_exact + 0.1, [&](const auto& sim, const StepInfo&) {
          const double rise = mean_z(sim, s.box.heel) - z0;
          if (t_hit < 0 && prev_t > 0.05 && prev_rise > 0 && rise <= 0) {
            t_hit = prev_t + (sim.time() - prev_t) * prev_rise / (prev_rise - rise);
          } else if (t_hit < 0) {
            omega_in = sim.angular_momentum(rock.pivot).y() / rock.I_O;
          } else if (omega_out == 0 && sim.time() >= t_hit + tau) {
            omega_out = sim.angular_momentum(heel_pivot).y() / rock.I_O - spin_down * (sim.time() - t_hit);
          }
          prev_rise = rise, prev_t = sim.time();
        });
        const double e = omega_in != 0 ? omega_out / omega_in : 0;  // the same sense of turning before and after
        report("S2 free rocking to %.3f rad (alpha %.4f), %s block, %s, dt %.2f ms: first impact at %.5f s, 1-DOF %.5f s "
               "(%+.3f%%); restitution %.3f, Housner %.3f",
               lift, rock.alpha, label, rigid ? "rigid" : "FE", 1e3 * dt, t_hit, t_exact, 100 * (t_hit / t_exact - 1), e,
               e_housner);
        INFO(label << (rigid ? " rigid" : " FE") << " dt " << dt);
        REQUIRE(t_hit > 0);
        CHECK_THAT(t_hit, Catch::Matchers::WithinRel(t_exact, dt < 5e-4 ? 1e-3 : 3e-3));
        CHECK(e > 0);  // it rocks on over the heel (no bounce back onto the toe) ...
        CHECK(e < 1);  // ... having lost energy
      }
}

// One impact at speed v flat onto the floor or against a wall (a box of `spec`, stiff law, mu 0.3):
// the deepest any node went into the struck plane, how far the centre of mass ended past where it
// started along the impact (0.2 s later), its speed then, and the simulation's impact sub-steps.
struct Impact {
  double deepest, moved, speed_after;
  long divided_steps, substeps;
};
Impact impact(const BoxSpec& spec, bool rigid, bool wall, double v, double dt, int max_substeps) {
  const double wall_x = 0.5 * spec.bx + tube_half_width;  // the box's +X face just touches it
  SimulationOptions options = options_dt(dt);
  options.max_impact_substeps = max_substeps;
  BlockScene<SpringDashpotLaw> s(spec, [&](const Box& b) { return stiff(b, 0.3); }, rigid, options, paper_newmark,
                                 SpringDashpotLaw{}, {floor_plane(), wall_plane(Vec3(wall_x, 0, 0), -Vec3::UnitX())});
  const Vec3 v0 = wall ? Vec3(v, 0, 0) : Vec3(0, 0, -v);
  s.sim->set_body_velocity(s.box.body, v0, Vec3::Zero(), s.box.cog);
  double deepest = 0;
  s.sim->run_until(0.2, [&](const auto& sim, const StepInfo&) {
    for (int n : s.sim->model().body(s.box.body).nodes) {
      const Vec3 x = sim.position(n);
      deepest = std::max(deepest, wall ? x.x() + tube_half_width - wall_x : tube_half_width - x.z());
    }
  });
  const double moved = wall ? s.com().x() - s.box.cog.x() : s.box.cog.z() - s.com().z();
  return {deepest, moved, s.com_velocity().norm(), s.sim->impact_steps(), s.sim->impact_substeps()};
}

// The stiff law's own travel, independently: the box as one mass M on the law's summed spring and
// dashpot (K = M g / 2.5 um, C = 2 zeta sqrt(K M), the dashpot's pull clamped), struck at v with gravity
// along the impact (floor) or across it (wall); RK4 at 1 us, the deepest x.
double one_dof_travel(double mass, double zeta, double v, bool gravity_along) {
  const double K = mass * 9.80665 / ContactParams::stiff_resting_penetration, C = 2 * zeta * std::sqrt(K * mass);
  const double g = gravity_along ? g0 : 0.0, h = 1e-6;
  const auto acc = [&](double x, double xd) { return g - std::max(0.0, K * x + C * xd) / mass; };
  double x = 0, xd = v, deepest = 0;
  for (int i = 0; i < 200000 && xd > -1; ++i) {
    const double k1x = xd, k1v = acc(x, xd);
    const double k2x = xd + 0.5 * h * k1v, k2v = acc(x + 0.5 * h * k1x, xd + 0.5 * h * k1v);
    const double k3x = xd + 0.5 * h * k2v, k3v = acc(x + 0.5 * h * k2x, xd + 0.5 * h * k2v);
    const double k4x = xd + h * k3v, k4v = acc(x + h * k3x, xd + h * k3v);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    xd += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    deepest = std::max(deepest, x);
    if (xd < 0 && x < deepest) break;
  }
  return deepest;
}

TEST_CASE("dropped and thrown at 5 and 10 m/s: at most 1 mm in with impact sub-steps, no tunnelling, stiff law",
          "[contact_dynamics][impact][stiff]") {
  // A box falling flat onto the floor, and thrown flat against a wall. With the contact inside the
  // step the dashpot stops the face within the step that it touches, but Newmark's kinematics still
  // move it (1 - beta/gamma) v dt = 0.47 v dt in that step: 2.3 mm at 5 m/s and 1 ms, whatever the law.
  // Undivided (max_impact_substeps 1, the paper's code) it is only asserted not to tunnel; divided
  // (SimulationOptions::impact_travel 0.5 mm a sub-step) the face goes at most 1 mm in at 5 m/s and
  // the rigid box's travel is the law's own, from the independent 1-DOF, within 25 %.
  const BoxSpec flat{0.4, 0.3, 0.3, Vec3::Zero(), 0, 0.05};
  for (const bool rigid : {true, false})
    for (const bool wall : {false, true}) {
      INFO((wall ? "wall " : "floor ") << (rigid ? "rigid" : "FE"));
      for (const double dt : {1e-3, 1e-4}) {
        const Impact undivided = impact(flat, rigid, wall, 5, dt, 1);
        report("S3 %s at 5 m/s, %s, dt %.2f ms, undivided: deepest %.3f mm, centre of mass 0.2 s later %.3f mm "
               "further in", wall ? "thrown at the wall" : "dropped", rigid ? "rigid" : "FE", 1e3 * dt,
               1e3 * undivided.deepest, 1e3 * undivided.moved);
        INFO("undivided, dt " << dt);
        CHECK(undivided.divided_steps == 0);
        CHECK(undivided.deepest < 5e-3);       // less than the 25 mm contact distance: no tunnelling
        CHECK(undivided.moved < 5e-3);         // it stays on its side
        CHECK(undivided.speed_after < 5);      // and leaves slower than it came: no energy made
      }
      for (const double v : {5.0, 10.0}) {
        const Impact divided = impact(flat, rigid, wall, v, 1e-3, 32);
        double travel = 0;
        if (rigid) {
          BlockScene<SpringDashpotLaw> probe(flat, [&](const Box& b) { return stiff(b, 0.3); }, true, options_dt(1e-3),
                                             paper_newmark);
          const auto& m = *probe.model;
          const double zeta = rocking_damping_ratio(m, probe.box.body, resting_nodes(m, probe.box.body));
          travel = one_dof_travel(probe.box.mass, zeta, v, !wall);
        }
        report("S3 %s at %.0f m/s, %s, dt 1 ms divided (%ld steps into %ld): deepest %.3f mm (1-DOF travel %.3f mm), "
               "centre of mass 0.2 s later %.3f mm further in, speed %.3f m/s",
               wall ? "thrown at the wall" : "dropped", v, rigid ? "rigid" : "FE", divided.divided_steps,
               divided.substeps, 1e3 * divided.deepest, 1e3 * travel, 1e3 * divided.moved, divided.speed_after);
        INFO("divided, v " << v);
        CHECK(divided.divided_steps > 0);
        CHECK(divided.deepest < (v < 6 ? 1e-3 : 2.5e-3));
        CHECK(divided.moved < 2.5e-3);
        CHECK(divided.speed_after < v);
        if (rigid) CHECK_THAT(divided.deepest, Catch::Matchers::WithinRel(travel, 0.25));
      }
    }
}

TEST_CASE("overturned by a pulse, a block lands on its side without energy from the contact, stiff law",
          "[contact_dynamics][rocking][impact][stiff]") {
  // Rectangular pulses of 1.2, 2 and 3 times the overturning threshold of the 1-DOF rocking
  // integration (Rocker): the block must tip over and end lying on its side (centre of gravity at
  // bx/2 above the floor's contact level), and the contact forces must never have done net positive
  // work. The corner and face that land do so between two steps; with the predictor's contacts for
  // the whole step (SimulationOptions::contact_iterations = 0) the contact made 10 to 53 % of the
  // block's initial energy in four of these six landings and two blocks were thrown back upright
  // (measured 2026-11-26). Resolved within the step, the tall block at 3 times still showed 2.6 to 9 %
  // net positive work as the pulse changed in its ninth digit (the variants `nudge` > 0) in the ledger's
  // contact_work, the trapezoidal rule on the increment, which under the paper's Newmark (gamma = 5/6)
  // is not what the scheme applies where a contact comes on or lets go; as applied
  // (contact_work_applied, Simulation::StepWork) every landing stays below zero (-0.001 %).
  struct Landing {
    BoxSpec spec;
    double level;
    int nudge;  // the pulse times 1 + nudge 1e-9
  };
  std::vector<Landing> landings;
  for (const auto& spec : {medium_block, tall_block})
    for (const double level : {1.2, 2.0, 3.0}) landings.push_back({spec, level, 0});
  for (int k = 1; k <= 5; ++k) landings.push_back({tall_block, 3.0, k});
  for (const auto& [spec, level, nudge] : landings) {
    BlockScene<SpringDashpotLaw> s(spec, [&](const Box& b) { return stiff(b, 2.0); }, true, options_dt(1e-3),
                                   paper_newmark);
    const Rocker rock = Rocker::of(*s.model, s.box, spec.bx);
    const double td = 1 / rock.p(), A = level * rock.pulse_threshold(td) * (1 + 1e-9 * nudge);
    s.sim->run_until(0.3);
    const double t0 = s.sim->time();
    s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 && t <= t0 + td ? -A : 0.0, 0, 0); });
    double made = -1e300, trapezoidal = -1e300;  // the largest net work of the contact forces so far
    s.sim->run_until(t0 + td + 3.0, [&](const auto& sim, const StepInfo&) {
      made = std::max(made, sim.energy().contact_work_applied);
      trapezoidal = std::max(trapezoidal, sim.energy().contact_work);
    });
    const double initial = s.sim->energy().initial_total, lying = 0.5 * spec.bx + tube_half_width;
    report("S4 pulse %.1f x threshold (1 + %d e-9), h %.1f m, rigid: largest net contact work as applied %.3g J "
           "(%.4f %% of %.1f J; trapezoidal estimate %.2f %%), centre of gravity %.4f m up (lying: %.4f m)",
           level, nudge, spec.h, made, 100 * made / initial, initial, 100 * trapezoidal / initial, s.com().z(), lying);
    INFO("h " << spec.h << " level " << level << " nudge " << nudge);
    CHECK(made < 1e-3 * initial);
    CHECK_THAT(s.com().z(), WithinAbs(lying, 0.005));
  }
}

TEST_CASE("the ledger's contact work as applied is what the items got: a block dropped flat, stiff law",
          "[contact_dynamics][impact][stiff][energy]") {
  // A rigid block (no rotation) thrown flat onto the floor from 10 mm up, under the paper's Newmark
  // (gamma = 5/6) and the stiff law: the only forces are gravity and the contact, so the contact's work
  // is the kinetic energy's change less gravity's, M g vz_mean dt per step (the velocity the scheme
  // moves a constant force through), here from the centre of mass's velocity. contact_work_applied
  // matches it to 4e-10 J (1e-11 of the energy); the trapezoidal contact_work is off by 4.9 to 70 J of
  // 4.8 to 119 J. Bound: 1e-7 of the kinetic energy thrown in (round-off over 3000 steps).
  for (const double dt : {1e-3, 1e-4})
    for (const double v : {1.0, 3.0, 5.0}) {
      BlockScene<SpringDashpotLaw> s(BoxSpec{}, [&](const Box& b) { return stiff(b, 0.3); }, true, options_dt(dt),
                                     paper_newmark);
      for (int k : s.model->body(s.box.body).nodes)
        s.sim->set_pose(k, s.model->node(k).X + Vec3(0, 0, 0.01), Mat3::Identity());
      s.sim->set_body_velocity(s.box.body, Vec3(0, 0, -v), Vec3::Zero(), s.box.cog);
      const double ke0 = 0.5 * s.box.mass * v * v;
      double ke_prev = -1, vz_prev = 0, ledger0 = 0, by_kinetic = 0, worst = 0, deepest = 0, trapezoidal = 0;
      s.sim->run_until(0.3, [&](const auto& sim, const StepInfo&) {
        const EnergyLedger e = sim.energy();
        const double vz = centre_of_mass_velocity(sim, s.box.body).z();
        if (ke_prev >= 0) {
          by_kinetic += e.kinetic - ke_prev + s.box.mass * g0 * 0.5 * (vz + vz_prev) * dt;
          worst = std::max(worst, std::abs(e.contact_work_applied - ledger0 - by_kinetic));
          trapezoidal = std::max(trapezoidal, std::abs(e.contact_work - e.contact_work_applied));
          deepest = std::min(deepest, by_kinetic);
        } else {
          ledger0 = e.contact_work_applied;
        }
        ke_prev = e.kinetic;
        vz_prev = vz;
      });
      report("S5 drop at %.0f m/s, dt %.0e: contact work as applied against the kinetic energy, largest difference "
             "%.3g J (of %.3g J thrown in; the contact took up to %.3g J; the trapezoidal estimate differs by up to %.3g J)",
             v, dt, worst, ke0, -deepest, trapezoidal);
      INFO("v " << v << " dt " << dt);
      CHECK(deepest < -0.5 * ke0);  // the block did land and the contact took its energy
      CHECK(worst < 1e-7 * ke0);
    }
}

}  // namespace stiff_law_tests
