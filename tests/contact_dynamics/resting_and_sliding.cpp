// A box frame on the floor in the full solver (Simulation + RoomContact), against closed forms:
//  1. resting: it settles to the penetration of its penalty law, sum alpha g = W, and stays at rest
//     for 10 s (no drift, no jitter), as a finite-element body and as a rigid body;
//  - the stability limit of the solver's explicit contact damping, which decides whether it does;
//  2. sliding onset: under a table acceleration it sticks at 0.97 mu g and slides at 1.03 mu g, and
//     a slow ramp finds the onset at mu g; the regularised paper friction creeps instead, at the
//     speed its regularisation predicts.
// Measured numbers: docs/contact/verification_contact.md (FFEM_REPORT=1 prints them).
#include <catch2/catch.hpp>

#include "dynamics_scenes.hpp"

using namespace ffem_dyn;

namespace resting_and_sliding_tests {  // this file's own names (its group compiles files in batches)

namespace {

// gamma of the paper's Newmark (paper_newmark: beta 4/9, gamma 5/6, carry-over of the unbalanced
// force, one solve per step: the scheme the paper's group uses).
constexpr double paper_gamma = 5.0 / 6.0;

}  // namespace

TEST_CASE("a block on the floor settles to sum(alpha g) = W and stays at rest for 10 s", "[contact_dynamics][rest]") {
  // Box 0.4 x 0.3 x 0.3 m of 50 x 30 x 2 tubes, 9.55 kg, 28 bottom nodes at L = 25 mm, released just
  // touching (g = 0). Paper law, q = 1: at rest every contact carries alpha g_i and the sum is the
  // weight, so the mean penetration ratio is g = M g / (n alpha); with alpha = W (the paper's rule)
  // g = 1/n. A rigid block has all g_i equal; the frame shares them unequally (its corners carry
  // the posts) but the sum is the same. dt = 1 ms. v_reg = 30 mm/s, above the explicit-damping
  // stability limit of 15.7 mm/s (next test case).
  const double dt = 1e-3, v_reg = 0.03;
  for (const bool rigid : {true, false}) {
    BlockScene<PaperLaw> s(BoxSpec{}, [&](const Box& b) { return paper_params(b.mass, 0.3, v_reg); }, rigid,
                           options_dt(dt), paper_newmark);
    const double n = double(s.box.bottom.size()), alpha = s.weight();  // alpha = W
    const double g_closed = s.weight() / (n * alpha);
    const Vec3 c0 = s.com();
    double late_speed = 0;  // largest nodal speed over the last second
    s.sim->run_until(10.0, [&](const auto& sim, const StepInfo&) {
      if (sim.time() > 9.0) late_speed = std::max(late_speed, max_speed(sim, s.box.body));
    });
    const double g_mean = 1 - mean_z(*s.sim, s.box.bottom) / tube_half_width;
    const double spread = (max_z(*s.sim, s.box.bottom) - min_z(*s.sim, s.box.bottom)) / tube_half_width;
    const Eigen::VectorXd f = contact_force_vector(*s.sim);
    Vec3 F = Vec3::Zero();
    for (int k = 0; k < s.model->num_nodes(); ++k) F += f.segment<3>(6 * k);
    const Vec3 drift = s.com() - c0;
    const double horizontal = std::hypot(drift.x(), drift.y());
    report("T1 rest (%s): n %d, M %.4f kg, g mean %.8f, closed form W/(n alpha) %.8f (ratio %.2e - 1), spread of g %.2e, "
           "sum Fz / W - 1 = %.2e, horizontal drift %.2e m, max speed in the last second %.2e m/s",
           rigid ? "rigid" : "FE", int(n), s.box.mass, g_mean, g_closed, g_mean / g_closed - 1, spread, F.z() / s.weight() - 1,
           horizontal, late_speed);
    // The transient (time constant 1.2 g L / v_reg = 36 ms, docs/contact/contact.md) is gone after 10 s: the
    // measured state is exact to round-off (1e-10 and below), the bounds leave room for it.
    CHECK(std::abs(g_mean / g_closed - 1) < 1e-6);
    CHECK(std::abs(F.z() / s.weight() - 1) < 1e-6);
    CHECK(std::abs(F.x()) + std::abs(F.y()) < 1e-6 * s.weight());
    CHECK(horizontal < 1e-4);   // no drift (the brief's bound; measured below 1e-15 m)
    CHECK(late_speed < 1e-6);   // no jitter: 1 um/s, against 10-20 mm/s when it chatters
    if (rigid) CHECK(spread < 1e-9);
    else CHECK(spread < 1e-3);  // the frame's own flexibility: 2e-5 of L measured
  }
}

TEST_CASE("explicit contact damping is stable exactly below its closed-form limit; implicit contact at any v_reg",
          "[contact_dynamics][rest][stability]") {
  // The regularised sign of the paper's F_N is a dashpot Dc g / v_reg below v_reg; summed over the
  // resting block it is c = 1.2 W / v_reg. Applied explicitly (RoomContact::implicit = false: forces
  // evaluated at the step's predictor, as the paper's code), the dashpot is stable only while
  // c dt / M < 2 / (1 + 2 gamma), i.e.
  // v_reg > (1 + 2 gamma)/2 * 1.2 g dt = 15.69 mm/s (dt 1 ms) and 1.569 mm/s (dt 0.1 ms), see
  // critical_v_reg(). Below it the block chatters in a limit cycle (amplitude a few v_reg, bounded by
  // the sign's saturation) and the friction, excited by it, lets it drift. 10 s, rigid block.
  struct Case {
    double dt, factor;
  };
  for (const Case c : {Case{1e-3, 0.95}, Case{1e-3, 1.05}, Case{1e-4, 0.95}, Case{1e-4, 1.05}}) {
    const double v_crit = critical_v_reg(1.2, c.dt, paper_gamma);
    const double v_reg = c.factor * v_crit;
    BlockScene<PaperLaw> s(BoxSpec{}, [&](const Box& b) { return paper_params(b.mass, 0.3, v_reg); }, true,
                           options_dt(c.dt), paper_newmark);
    s.sim->contact().implicit = false;
    double before = 0, last = 0;  // largest nodal speed in the second before the last, and in the last
    const double t_end = c.dt < 5e-4 ? 3.0 : 10.0;
    s.sim->run_until(t_end, [&](const auto& sim, const StepInfo&) {
      const double v = max_speed(sim, s.box.body);
      if (sim.time() > t_end - 1) last = std::max(last, v);
      else if (sim.time() > t_end - 2) before = std::max(before, v);
    });
    report("T1b stability: dt %.0e s, v_reg = %.2f x %.5f m/s: max speed in the last two seconds %.2e, %.2e m/s", c.dt,
           c.factor, v_crit, before, last);
    // Chattering: 0.5-5 mm/s, sustained. Stable: the oscillation is gone and what is left decays:
    // at dt 1 ms round-off (1e-13 m/s) after 10 s; at dt 0.1 ms the last of the settling creep, whose
    // time constant 1.2 g L / v_reg is 0.6 s there (5e-6 m/s after 3 s, falling 5x per second).
    // The 5% margins around the limit are where the linear analysis must hold (the penalty spring,
    // omega dt = 0.1 at 1 ms, shifts it by less than that).
    if (c.factor < 1) {
      CHECK(last > 1e-4);
      CHECK(last > 0.5 * before);
    } else {
      CHECK(last < 1e-5);
      CHECK((last < 1e-9 || last < 0.5 * before));
    }
  }
  // A finite-element body: each node is its own mass, and at small dt its beams add little to the
  // effective mass of the implicit step (K beta dt^2). A bottom node carries alpha g_i = W/28 on
  // m_i = 0.12 kg, so its dashpot Dc g_i / v_reg needs v_reg > (1 + 2 gamma)/2 * 1.2 (W/28)/m_i dt:
  // 9.0 mm/s at dt = 0.2 ms (the beams lower it a little: measured between 8.0 and 8.5 mm/s).
  for (const double factor : {0.85, 1.15}) {
    const double dt = 2e-4;
    double v_crit = 0;
    BlockScene<PaperLaw> s(
        BoxSpec{},
        [&](const Box& b) {
          const double m_node = elastic_steel().rho * tube().A * 0.05;  // two half elements of 50 mm
          const double load_per_mass = b.mass * g0 / double(b.bottom.size()) / m_node;
          v_crit = critical_v_reg(1.2 * load_per_mass / g0, dt, paper_gamma);
          return paper_params(b.mass, 0.3, factor * v_crit);
        },
        false, options_dt(dt), paper_newmark);
    s.sim->contact().implicit = false;
    double last = 0;
    s.sim->run_until(2.0, [&](const auto& sim, const StepInfo&) {
      if (sim.time() > 1.5) last = std::max(last, max_speed(sim, s.box.body));
    });
    report("T1b stability, FE block: dt 2e-4 s, v_reg = %.2f x %.5f m/s (per-node estimate): max speed in the last 0.5 s "
           "%.2e m/s",
           factor, v_crit, last);
    // Chattering: 2.3 mm/s; stable: round-off. 15% margins: the estimate neglects the beams.
    if (factor < 1) CHECK(last > 1e-4);
    else CHECK(last < 1e-6);
  }
  // The paper's settings (dt 1 ms, v_reg 1 mm/s, the scene files' default) are 16x below the explicit
  // limit: applied explicitly the block never settles; inside the implicit step (the default) the
  // damping is the dashpot it is at the evaluated speed and the block comes to rest, rigid or FE.
  for (const bool implicit : {false, true})
    for (const bool rigid : {true, false}) {
      if (!implicit && !rigid) continue;
      BlockScene<PaperLaw> s(BoxSpec{}, [&](const Box& b) { return paper_params(b.mass, 0.3, 1e-3); }, rigid,
                             options_dt(1e-3), paper_newmark);
      s.sim->contact().implicit = implicit;
      const Vec3 c0 = s.com();
      double late_speed = 0;
      s.sim->run_until(10.0, [&](const auto& sim, const StepInfo&) {
        if (sim.time() > 9.0) late_speed = std::max(late_speed, max_speed(sim, s.box.body));
      });
      const Vec3 drift = s.com() - c0;
      report("T1b default v_reg 1 mm/s at dt 1 ms, %s contact, %s block: max speed in the last second %.2e m/s, "
             "horizontal drift after 10 s %.2e m, mean g / closed form %.4f",
             implicit ? "implicit" : "explicit", rigid ? "rigid" : "FE", late_speed, std::hypot(drift.x(), drift.y()),
             (1 - mean_z(*s.sim, s.box.bottom) / tube_half_width) * double(s.box.bottom.size()));
      if (!implicit) {
        CHECK(late_speed > 1e-3);
      } else {
        CHECK(late_speed < 1e-6);  // 1e-8 m/s measured: settled
        CHECK(std::hypot(drift.x(), drift.y()) < 1e-4);
      }
    }
  // The explicit cases above, implicit: stable on both sides of the explicit limit.
  for (const double dt : {1e-3, 1e-4}) {
    const double v_reg = 0.5 * critical_v_reg(1.2, dt, paper_gamma);
    BlockScene<PaperLaw> s(BoxSpec{}, [&](const Box& b) { return paper_params(b.mass, 0.3, v_reg); }, true,
                           options_dt(dt), paper_newmark);
    double last = 0;
    const double t_end = 3.0;
    s.sim->run_until(t_end, [&](const auto& sim, const StepInfo&) {
      if (sim.time() > t_end - 1) last = std::max(last, max_speed(sim, s.box.body));
    });
    report("T1b implicit: dt %.0e s, v_reg half the explicit limit: max speed in the last second %.2e m/s", dt, last);
    CHECK(last < 1e-4);  // chattering: above 1e-4 (explicit, first loop)
  }
}

TEST_CASE("sliding starts at mu g: sticks at 0.97 mu g, slides at 1.03 mu g", "[contact_dynamics][friction]") {
  // Law: StickSlipLaw (the paper's normal response with a stick-slip Coulomb friction). Its friction
  // is a spring-dashpot held inside the cone |F| <= mu N, so below mu N nothing moves but the
  // spring's elastic deflection, and it slides only when every contact sits on the cone, i.e. at
  // the total mu sum(N) = mu W. The paper's regularised friction cannot answer "not below": below
  // v_reg it is a dashpot and creeps under any force (checked at the end).
  // Table acceleration: ramp from 0 to the level over 1 s (quasi-static for the tangential mode of
  // 24 Hz), then held 2 s. Tangential spring: omega_t = 150 rad/s, 70% damping; elastic deflection
  // F / (n k_t) = 0.13 mm at 0.97 mu W (the lightly loaded contacts slip first and the others take
  // their share, so up to about 3 times that). dt 1 ms, v_reg 30 mm/s (stable normal damping).
  const double mu = 0.3, dt = 1e-3, v_reg = 0.03, ramp = 1.0, hold = 2.0;
  auto params = [&](const Box& b) {
    ContactParams p = paper_params(b.mass, mu, v_reg);
    set_stick_spring(p, b.mass, int(b.bottom.size()), 150, 0.7);
    return p;
  };
  for (const bool rigid : {true, false}) {
    for (const double level : {0.97, 1.03}) {
      BlockScene<StickSlipLaw> s(BoxSpec{}, params, rigid, options_dt(dt), paper_newmark);
      s.sim->run_until(0.5);  // settle
      const double t0 = s.sim->time(), A = level * mu * g0;
      s.sim->set_table_acceleration(
          [=](double t) { return Vec3(A * std::clamp((t - t0) / ramp, 0.0, 1.0), 0, 0); });
      const double x0 = s.com().x();
      s.sim->run_until(t0 + ramp);
      const double x_ramp = s.com().x() - x0;
      s.sim->run_until(t0 + ramp + hold);
      const double x_end = s.com().x() - x0, v_end = s.com_velocity().x();
      // Sliding (relative to the table) under a held level: relative acceleration -(level - 1) mu g
      // from the moment the ramp passed mu g (t = ramp / level).
      const double t_slide = t0 + ramp + hold - (t0 + ramp / level);
      const double v_closed = -(level - 1) * mu * g0 * t_slide;
      report("T2 level %.2f mu g (%s): x at ramp end %.3e m, after the %.0f s hold %.3e m, v %.4e m/s (closed form %.4e)",
             level, rigid ? "rigid" : "FE", x_ramp, hold, x_end, v_end, level > 1 ? v_closed : 0.0);
      if (level < 1) {
        CHECK(std::abs(x_end) < 1e-3);              // the elastic stick deflection (0.4 mm measured)
        CHECK(std::abs(x_end - x_ramp) < 5e-5);     // and no creep during the hold (15 um measured)
        CHECK(std::abs(v_end) < 1e-5);
      } else {
        CHECK(x_end < -0.1);                        // 0.18 m: sliding
        CHECK_THAT(v_end, Catch::Matchers::WithinRel(v_closed, 0.03));  // 0.1% measured
      }
    }
  }
}

TEST_CASE("a slow ramp of the table acceleration finds the sliding onset at mu g", "[contact_dynamics][friction]") {
  // a(t) = r t with r such that 1.1 mu g is reached after 4 s. For a rigid Coulomb block that starts
  // to slide at t_on the relative velocity is v(t) = -r (t - t_on)^2 / 2, so the onset is
  // extrapolated from the first time |v| exceeds 5 mm/s: t_on = t - sqrt(2 |v| / r), a_on = r t_on.
  // Both normal forces the stick-slip cone can use are tried: the penalty part alpha g (paper eq. 3,
  // the law's default) and the total normal force.
  const double mu = 0.3, dt = 1e-3, v_reg = 0.03, r = 1.1 * mu * g0 / 4.0;
  for (const FrictionNormal normal : {FrictionNormal::penalty, FrictionNormal::total}) {
    StickSlipLaw law;
    law.friction_part().normal = normal;
    BlockScene<StickSlipLaw> s(
        BoxSpec{},
        [&](const Box& b) {
          ContactParams p = paper_params(b.mass, mu, v_reg);
          set_stick_spring(p, b.mass, int(b.bottom.size()), 150, 0.7);
          return p;
        },
        true, options_dt(dt), paper_newmark, law);
    s.sim->run_until(0.5);
    const double t0 = s.sim->time();
    s.sim->set_table_acceleration([=](double t) { return Vec3(r * std::max(0.0, t - t0), 0, 0); });
    double a_on = -1;
    s.sim->run_until(t0 + 4.5, [&](const auto& sim, const StepInfo&) {
      const double v = centre_of_mass_velocity(sim, s.box.body).x();
      if (a_on < 0 && std::abs(v) > 5e-3) a_on = r * (sim.time() - t0 - std::sqrt(2 * std::abs(v) / r));
    });
    report("T2 ramp onset (cone on the %s normal force): a_on / (mu g) = %.5f", normal == FrictionNormal::penalty ? "penalty" : "total",
           a_on / (mu * g0));
    // The brief's 2%; the onset is found within 0.5% (the extrapolation assumes a rigid Coulomb
    // block from t_on on, the stick spring's partial slip smears it by a few tenths of a percent).
    CHECK_THAT(a_on / (mu * g0), Catch::Matchers::WithinAbs(1.0, 0.02));
  }
}

TEST_CASE("the regularised paper friction creeps below mu g at v = F v_reg / (mu W)", "[contact_dynamics][friction]") {
  // Below v_reg the paper's friction (ramp regularisation) is -mu W v / v_reg summed over the block:
  // a dashpot. A held force F < mu W therefore makes the block creep at the steady speed
  // v = F v_reg / (mu W) (time constant v_reg / (mu g) = 10 ms), here 0.97 v_reg. This is why test 2
  // uses the stick-slip law for "not below".
  const double mu = 0.3, dt = 1e-3, v_reg = 0.03, level = 0.97;
  BlockScene<PaperLaw> s(BoxSpec{}, [&](const Box& b) { return paper_params(b.mass, mu, v_reg); }, true, options_dt(dt),
                         paper_newmark);
  s.sim->run_until(0.5);
  const double t0 = s.sim->time(), A = level * mu * g0;
  s.sim->set_table_acceleration([=](double t) { return Vec3(A * std::clamp((t - t0) / 1.0, 0.0, 1.0), 0, 0); });
  s.sim->run_until(t0 + 3.0);
  const double v = -s.com_velocity().x(), v_closed = level * v_reg;
  report("T2 paper friction at 0.97 mu g: creep speed %.5f m/s, closed form 0.97 v_reg = %.5f m/s", v, v_closed);
  // The creep speed follows from the force balance alone: exact to 1e-5 measured; 1e-3 leaves room
  // for the normal force's split between penalty and damping while the tilt settles.
  CHECK_THAT(v, Catch::Matchers::WithinRel(v_closed, 1e-3));
}

}  // namespace resting_and_sliding_tests
