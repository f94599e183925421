// Rigid-body mechanics of a block on a shaking floor, in the full solver, against closed forms:
//  3. a rectangular acceleration pulse: residual slip V^2 / (2 mu g) (1 - mu / A), V = A g t0;
//  4. rocking onset of a tall block at g b / h (and its correction for the penalty's compliance);
//  7. the same pulse with three contact laws on one scene, each against the closed form.
// Measured numbers: docs/contact/verification_contact.md (FFEM_REPORT=1 prints them).
#include <catch2/catch.hpp>

#include "dynamics_scenes.hpp"

#include <string>

using namespace ffem_dyn;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace pulse_and_rocking_tests {  // this file's own names (its group compiles files in batches)

namespace {


// The pulse of tests 3 and 7: A = 0.5 g during t0 = 0.3 s on a 0.4 x 0.3 x 0.3 m block, mu = 0.3.
// In the table frame the block gets -M A g while the pulse lasts and friction mu W against its
// sliding: it slides backwards at (A - mu) g, then decelerates at mu g until it is at rest on the
// table again, after a total slip of
//     s = (A - mu) g t0^2 / 2 + ((A - mu) g t0)^2 / (2 mu g) = V^2 / (2 mu g) (1 - mu / A),  V = A g t0.
constexpr double pulse_A = 0.5, pulse_mu = 0.3, pulse_t0 = 0.3;
double pulse_closed_form(double mu) {
  const double V = pulse_A * g0 * pulse_t0;
  return V * V / (2 * mu * g0) * (1 - mu / pulse_A);
}

struct PulseResult {
  double slip = 0;             // m, final slip relative to the table (positive backwards)
  double speed_after = 0;      // m/s, the block's speed on the table 1.2 s after the pulse
  double penalty_share = 0;    // time mean of sum(alpha g) / W while sliding (paper laws)
  double sliding_time = 0;     // s
};

// Runs the pulse on a rigid block with the given law and parameters. dt = 0.2 ms and v_reg = 5 mm/s:
// the explicit contact damping is stable for v_reg > 3.1 mm/s at this step (resting_and_sliding.cpp),
// and the regularisation's own error, the friction missing while the block passes through
// |v| < v_reg at the start, is about mu v_reg / A x (the sliding time) = 1.5 mm (1%).
template <class Law>
PulseResult run_pulse(const Law& law, const std::function<void(ContactParams&, const Box&)>& tune = {},
                      bool rigid = true, double v_reg = 5e-3) {
  const double dt = 2e-4;
  BlockScene<Law> s(
      BoxSpec{},
      [&](const Box& b) {
        ContactParams p = paper_params(b.mass, pulse_mu, v_reg);
        if (tune) tune(p, b);
        return p;
      },
      rigid, options_dt(dt), paper_newmark, law);
  s.sim->run_until(0.5);  // settle from first touch
  const double ts = s.sim->time(), x0 = s.com().x();
  // The table acceleration is sampled at the end of each step: the steps ending in (ts, ts + t0]
  // carry the pulse, 1500 steps of 0.2 ms = t0 exactly.
  s.sim->set_table_acceleration([=](double t) {
    return Vec3(t > ts + 1e-9 && t <= ts + pulse_t0 + 1e-9 ? pulse_A * g0 : 0.0, 0, 0);
  });
  PulseResult r;
  double share_time = 0;
  const double alpha = s.weight();  // every preset here uses alpha = W
  s.sim->run_until(ts + 1.5, [&](const auto& sim, const StepInfo&) {
    if (std::abs(centre_of_mass_velocity(sim, s.box.body).x()) < 1e-2) return;
    double pen = 0;
    for (int n : s.box.bottom) pen += alpha * std::max(0.0, 1 - sim.position(n).z() / tube_half_width);
    r.penalty_share += pen / s.weight() * dt;
    share_time += dt;
  });
  r.slip = x0 - s.com().x();
  r.speed_after = std::abs(s.com_velocity().x());
  r.penalty_share /= share_time;
  r.sliding_time = share_time;
  return r;
}

}  // namespace

TEST_CASE("a rectangular pulse leaves the residual slip V^2/(2 mu g) (1 - mu/A)", "[contact_dynamics][pulse]") {
  const double closed = pulse_closed_form(pulse_mu);  // 0.14710 m
  // (a) The paper's law with its friction cone on the total normal force (the law's runtime
  // switch): the closed form's friction mu W holds at every instant of the slide.
  PaperLaw total;
  total.friction_part().normal = FrictionNormal::total;
  const PulseResult a = run_pulse(total);
  // (b) The paper's law as written (eq. 3: friction on the penalty part alpha g). The pulse pitches
  // the block; the paper's normal damping is Coulomb-like (constant magnitude Dc g), so the tilt
  // relaxes only by the regularisation's creep, and meanwhile the damping part carries about 2% of
  // the weight: the friction is mu x (penalty share) x W. The closed form with that effective
  // coefficient, mu_eff = mu x (mean penalty share while sliding), accounts for it.
  const PulseResult b = run_pulse(PaperLaw{});
  const double closed_b = pulse_closed_form(pulse_mu * b.penalty_share);
  report("T3 pulse A %.1f g, t0 %.1f s, mu %.1f: closed form %.5f m", pulse_A, pulse_t0, pulse_mu, closed);
  report("T3   paper law, cone on total N: slip %.5f m (%+.2f%%), speed afterwards %.1e m/s", a.slip,
         100 * (a.slip / closed - 1), a.speed_after);
  report("T3   paper law as written (cone on alpha g): slip %.5f m (%+.2f%%); mean penalty share while sliding %.4f; "
         "closed form with mu_eff = %.4f: %.5f m (%+.2f%%)",
         b.slip, 100 * (b.slip / closed - 1), b.penalty_share, pulse_mu * b.penalty_share, closed_b,
         100 * (b.slip / closed_b - 1));
  CHECK_THAT(a.slip, WithinRel(closed, 0.03));    // the brief's 3%; +0.6% measured (regularisation)
  CHECK(a.speed_after < 1e-3);                    // back at rest on the table (creep of the tilt only)
  CHECK_THAT(b.slip, WithinRel(closed, 0.05));    // +3.4% measured, explained by the next line
  CHECK_THAT(b.slip, WithinRel(closed_b, 0.015)); // +0.3% measured
}

TEST_CASE("the finite-element block slides like the rigid block", "[contact_dynamics][pulse]") {
  // The same pulse on the box frame as a finite-element body. Its bottom nodes each carry W/28 on
  // 0.12 kg, 2.9 times g per unit mass, so the explicit-damping limit per node is 2.9 times the
  // rigid block's: about 9 mm/s at dt 0.2 ms (resting_and_sliding.cpp). v_reg = 12 mm/s for both
  // bodies here. Below that limit the frame chatters and its slip is off by several percent (with
  // the paper's law as written at v_reg = 5 mm/s the chattering frame slid 5.5% less than the rigid
  // block).
  PaperLaw law;
  law.friction_part().normal = FrictionNormal::total;
  const PulseResult fe = run_pulse(law, {}, false, 12e-3);
  const PulseResult rigid = run_pulse(law, {}, true, 12e-3);
  const double closed = pulse_closed_form(pulse_mu);
  report("T3 pulse, v_reg 12 mm/s: FE block slip %.5f m, rigid block %.5f m (FE / rigid - 1 = %.2e), closed form %.5f m "
         "(FE %+.2f%%)",
         fe.slip, rigid.slip, fe.slip / rigid.slip - 1, closed, 100 * (fe.slip / closed - 1));
  CHECK_THAT(fe.slip, WithinRel(rigid.slip, 5e-3));  // the frame's flexibility: 3e-4 measured
  // The regularisation's share grows with v_reg (at most mu v_reg / A x 0.5 s = 3.6 mm, 2.4%):
  // +1.6% measured.
  CHECK_THAT(fe.slip, WithinRel(closed, 0.04));
}

TEST_CASE("two laws on one scene: the pulse with the paper law and the alternatives", "[contact_dynamics][pulse][laws]") {
  // One scene (block, pulse, dt, v_reg), three law types instantiated from the same code:
  //  - PaperLaw, cone on the total normal force (as in the pulse test);
  //  - StickSlipLaw (paper normal response, stick-slip friction on the total normal force):
  //    omega_t = 300 rad/s, 70% damping. Until its spring reaches mu N the block follows the table,
  //    so the friction is missing for a few ms at the start, like the regularisation's;
  //  - SpringDashpotLaw: k_lin = alpha / L per contact (the paper's static stiffness: equal resting
  //    penetration), c_lin for 50% of critical on the block's vertical mode, regularised Coulomb
  //    friction on the total normal force (mu N v / sqrt(v^2 + v_reg^2)).
  // Each is checked against the closed form (3%) and the differences between them reported.
  const double closed = pulse_closed_form(pulse_mu);
  PaperLaw paper;
  paper.friction_part().normal = FrictionNormal::total;
  StickSlipLaw stick;
  stick.friction_part().normal = FrictionNormal::total;
  const PulseResult p = run_pulse(paper);
  const PulseResult st = run_pulse(stick, [](ContactParams& c, const Box& b) {
    set_stick_spring(c, b.mass, int(b.bottom.size()), 300, 0.7);
  });
  const PulseResult sd = run_pulse(SpringDashpotLaw{}, [](ContactParams& c, const Box& b) {
    const double n = double(b.bottom.size());
    c.k_lin = c.alpha / tube_half_width;
    c.c_lin = 2 * 0.5 * std::sqrt(c.k_lin * n * b.mass) / n;
  });
  report("T7 pulse, closed form %.5f m: PaperLaw %.5f (%+.2f%%), StickSlipLaw %.5f (%+.2f%%), SpringDashpotLaw %.5f "
         "(%+.2f%%); StickSlip - Paper = %+.2f mm, SpringDashpot - Paper = %+.2f mm",
         closed, p.slip, 100 * (p.slip / closed - 1), st.slip, 100 * (st.slip / closed - 1), sd.slip,
         100 * (sd.slip / closed - 1), 1e3 * (st.slip - p.slip), 1e3 * (sd.slip - p.slip));
  CHECK_THAT(p.slip, WithinRel(closed, 0.03));
  CHECK_THAT(st.slip, WithinRel(closed, 0.03));
  CHECK_THAT(sd.slip, WithinRel(closed, 0.03));
  // The laws differ only by how the friction builds up at the start and dies out at the end of the
  // slide: a few millimetres out of 147.
  CHECK(std::abs(st.slip - p.slip) < 5e-3);
  CHECK(std::abs(sd.slip - p.slip) < 5e-3);
}

TEST_CASE("a tall block starts to rock at a table acceleration g b/h, and not below", "[contact_dynamics][rocking]") {
  // Block 0.3 x 0.3 m, 1.0 m between bottom and top centre lines, 15.3 kg. Its bottom edges along X
  // are lifted by 0.1 m (the posts reach the floor), so the floor contacts lie on the two pivot
  // lines x = -b/2 (heel) and x = +b/2 (toe), 7 nodes each, b = 0.3 m. mu = 0.6 > b/h: it rocks
  // before it slides. Stick-slip friction (no creep while it leans).
  // Rigid contact: the heel unloads when the inertial moment M a h_cg reaches M g b/2, a = g b/h with
  // h = 2 h_cg (h_cg: height of the centre of gravity above the contact nodes' centre lines).
  // Penalty contact is compliant: the block leans by theta = 2 W L / (n alpha b) before the heel
  // unloads, the centre of gravity moves towards the toe by theta h_cg, and the onset drops to
  //     a_c = g b/h (1 - 4 W L h_cg / (n alpha b^2)).
  // With the paper's alpha = W that is 4% lower (checked below); alpha = 10 W makes it 0.4%, so the
  // rigid closed form is tested at 0.97 and 1.03.
  // Table acceleration along -X (the block leans towards +X, the heel at -X lifts), ramped over 2 s
  // (slow against the rocking mode) and held 1 s. Uplift: every heel node out of contact (l > L)
  // and the heel risen by more than 5 mm; no uplift: every heel node in contact throughout and the
  // heel never 1 mm above its resting height.
  const double mu = 0.6, dt = 1e-3, v_reg = 0.03;
  BoxSpec spec;
  spec.bx = 0.3;
  spec.by = 0.3;
  spec.h = 1.0;
  spec.raise = 0.1;
  auto scene = [&](double alpha_over_weight) {
    return BlockScene<StickSlipLaw>(
        spec,
        [&](const Box& b) {
          ContactParams p = paper_params(b.mass, mu, v_reg);
          p.alpha *= alpha_over_weight;
          p.Dc *= alpha_over_weight;
          set_stick_spring(p, b.mass, int(b.bottom.size()), 150, 0.7);
          return p;
        },
        true, options_dt(dt), paper_newmark);
  };
  struct Onset {
    double b_over_h, correction;
  };
  auto closed_forms = [&](const Box& b, double alpha_over_weight) {
    const double h_cg = b.cog.z() - tube_half_width, n = double(b.bottom.size());
    return Onset{spec.bx / (2 * h_cg), 4 * tube_half_width * h_cg / (n * alpha_over_weight * spec.bx * spec.bx)};
  };

  SECTION("levels 0.97 and 1.03 of g b/h (alpha = 10 W)") {
    for (const double level : {0.97, 1.03}) {
      auto s = scene(10.0);
      REQUIRE(s.box.heel.size() == 7);
      REQUIRE(s.box.bottom.size() == 14);
      const Onset c = closed_forms(s.box, 10.0);
      s.sim->run_until(0.5);
      const double z_heel = max_z(*s.sim, s.box.heel), t0 = s.sim->time();
      const double a = level * g0 * c.b_over_h;
      s.sim->set_table_acceleration([=](double t) { return Vec3(-a * std::clamp((t - t0) / 2.0, 0.0, 1.0), 0, 0); });
      double rise = 0;
      int fewest_heel_contacts = int(s.box.heel.size());
      s.sim->run_until(t0 + 3.0, [&](const auto& sim, const StepInfo&) {
        rise = std::max(rise, max_z(sim, s.box.heel) - z_heel);
        int in_contact = 0;
        for (int n : s.box.heel) in_contact += sim.position(n).z() <= tube_half_width;
        fewest_heel_contacts = std::min(fewest_heel_contacts, in_contact);
      });
      report("T4 rocking, level %.2f g b/h (b/h = %.4f, compliance correction %.2f%%): heel rise %.3e m, fewest heel "
             "contacts %d of %zu",
             level, c.b_over_h, 100 * c.correction, rise, fewest_heel_contacts, s.box.heel.size());
      if (level < 1) {
        CHECK(fewest_heel_contacts == int(s.box.heel.size()));
        CHECK(rise < 1e-3);   // 0.18 mm measured: the toe's extra penetration tilting the block
      } else {
        CHECK(fewest_heel_contacts == 0);
        CHECK(rise > 5e-3);   // 52 mm after the 1 s hold: it is tipping over
      }
    }
  }

  SECTION("a slow ramp finds the onset at the compliance-corrected closed form") {
    // a(t) = r t up to 1.1 g b/h in 6 s; onset: the first step with every heel node out of contact.
    for (const double alpha_over_weight : {1.0, 10.0}) {
      auto s = scene(alpha_over_weight);
      const Onset c = closed_forms(s.box, alpha_over_weight);
      s.sim->run_until(0.5);
      const double t0 = s.sim->time(), r = 1.1 * g0 * c.b_over_h / 6.0;
      s.sim->set_table_acceleration([=](double t) { return Vec3(-r * std::max(0.0, t - t0), 0, 0); });
      double a_on = -1;
      s.sim->run_until(t0 + 6.0, [&](const auto& sim, const StepInfo&) {
        if (a_on > 0) return;
        bool lifted = true;
        for (int n : s.box.heel) lifted = lifted && sim.position(n).z() > tube_half_width;
        if (lifted) a_on = r * (sim.time() - t0);
      });
      const double rigid_form = a_on / (g0 * c.b_over_h), corrected = rigid_form / (1 - c.correction);
      report("T4 rocking ramp, alpha = %.0f W: onset a / (g b/h) = %.5f, / corrected closed form (1 - %.4f) = %.5f",
             alpha_over_weight, rigid_form, c.correction, corrected);
      // The corrected form within 1% (the ramp's lag behind the quasi-static state and the
      // lean's second-order terms: 0.05-0.3% measured); the rigid form within the brief's 3% only when
      // the penalty is stiff enough.
      CHECK_THAT(corrected, WithinAbs(1.0, 0.01));
      if (alpha_over_weight >= 10) CHECK_THAT(rigid_form, WithinAbs(1.0, 0.03));
      else CHECK(rigid_form < 0.97);
    }
  }
}

}  // namespace pulse_and_rocking_tests
