// Contact inside the implicit step (docs/contact/implicit_contact.md), against closed forms and an
// independent 1-DOF integration, over several laws, sizes, friction coefficients and amplitudes:
//  1. at rest 10 s under gravity, every law: drift at most 0.1 mm, nodal speeds at most 1 mm/s;
//  2. held by 0.9 mu g for 10 s: no creep beyond the first elastic step (0.1 mm);
//  3. harmonic sliding in the continuous regime (1.5 to 4 mu g): peak-to-peak within 1 % of an exact
//     1-DOF Coulomb integration;
//  4. overturning under a suddenly applied constant table acceleration with the stiff parameters:
//     above g b/h (1 % rigid, 2 % FE) it tips over; below (1 % rigid, 4 % FE), it does not; 2 % below,
//     a frame rises as the same frame iterated to equilibrium at every step.
// Measured numbers: docs/contact/verification_contact.md (FFEM_REPORT=1 prints them).
#include <catch2/catch.hpp>

#include <numbers>
#include <string_view>
#include <vector>

#include "dynamics_scenes.hpp"

using namespace ffem_dyn;

namespace holding_still_tests {  // this file's own names (its group compiles files in batches)

namespace {

// Per-law parameters for a box of mass M on n resting nodes, friction mu, sticking friction (the
// paper's: paper_stick, dynamics_scenes.hpp).
// The `stiff` rule as the scenes use it (set_stiff_contact): 2.5 um under the weight shared by the
// resting nodes, damped critically for the item's vertical and rocking motion.
ContactParams stiff(const Box& b, double mu) {
  ContactParams p = paper_stick(b, mu);
  set_stiff_contact(*b.model, b.body, p);
  return p;
}
ContactParams stick_slip(const Box& b, double mu) {
  ContactParams p = paper_params(b.mass, mu, 1e-3);
  set_stick_spring(p, b.mass, int(b.bottom.size()), 150, 0.7);
  return p;
}

const BoxSpec small_box{};                                  // 0.4 x 0.3 x 0.3 m
const BoxSpec tall_box{0.45, 0.4, 1.2, Vec3::Zero(), 0, 0.1};  // the tall cabinet's proportions

// Runs `check(name, scene)` for every law the scenes offer, with its parameters for friction mu.
template <class Check>
void for_every_law(const BoxSpec& box, bool rigid, double mu, Check&& check) {
  const SimulationOptions o = options_dt(1e-3);
  {
    BlockScene<PaperLaw> s(box, [&](const Box& b) { return paper_stick(b, mu); }, rigid, o, paper_newmark);
    check("paper", s);
  }
  {
    BlockScene<PaperAnisotropicFloorLaw> s(
        box,
        [&](const Box& b) {
          ContactParams p = paper_stick(b, mu);
          p.mu_short = 0.8 * mu;
          return p;
        },
        rigid, o, paper_newmark);
    check("paper_anisotropic", s);
  }
  {
    BlockScene<SpringDashpotLaw> s(box, [&](const Box& b) { return stiff(b, mu); }, rigid, o, paper_newmark);
    check("stiff", s);
  }
  {
    BlockScene<HuntCrossleyLaw> s(box, [&](const Box& b) { return stiff(b, mu); }, rigid, o, paper_newmark);
    check("hunt_crossley", s);
  }
  {
    BlockScene<StickSlipLaw> s(box, [&](const Box& b) { return stick_slip(b, mu); }, rigid, o, paper_newmark);
    check("stick_slip", s);
  }
}

// Exact 1-DOF Coulomb block on a table moving with a(t) = A sin(w t): x is the block's displacement
// relative to the table; it sticks while |a| <= mu g at zero relative speed. Small steps with the
// velocity's zero crossings caught: the peak-to-peak x over the last period of `periods`.
double coulomb_peak_to_peak(double A, double w, double mu, int periods) {
  const double dt = 1e-6, T = 2 * std::numbers::pi / w, mug = mu * g0;
  double x = 0, v = 0, lo = 1e300, hi = -1e300;
  bool stuck = true;
  const long n = std::lround(periods * T / dt);
  for (long i = 0; i < n; ++i) {
    const double t = i * dt, a = A * std::sin(w * (t + 0.5 * dt));
    if (stuck && std::abs(a) > mug) stuck = false;
    if (!stuck) {
      const double dir = v != 0 ? (v > 0 ? 1.0 : -1.0) : (a > 0 ? -1.0 : 1.0);  // slides against a
      const double v1 = v + (-a - mug * dir) * dt;
      if (v != 0 && v1 * v < 0) {  // stops within the step
        x += 0.5 * v * (v / (v - v1)) * dt;
        v = 0;
        stuck = std::abs(a) <= mug;
      } else {
        x += 0.5 * (v + v1) * dt;
        v = v1;
      }
    }
    if (t >= (periods - 1) * T) lo = std::min(lo, x), hi = std::max(hi, x);
  }
  return hi - lo;
}

}  // namespace

TEST_CASE("every law holds a block still for 10 s under gravity", "[contact_dynamics][rest][implicit]") {
  // Released touching the floor with a horizontal push of 5 mm/s (so that symmetry alone cannot keep
  // it in place), each block must stop, then stay: drift between 1 s and 10 s at most 0.1 mm, nodal
  // speeds in the last second at most 1 mm/s (the bounds). Explicit contact at the paper's
  // settings drifted 24.7 mm here, jittering at 20 mm/s (resting_and_sliding.cpp).
  for (const auto& [box, label] : {std::pair{small_box, "small"}, std::pair{tall_box, "tall"}})
    for (const bool rigid : {true, false})
      // label by an init-capture: clang 14 (the sanitized build) cannot capture a structured binding.
      for_every_law(box, rigid, 0.3, [&, label = label](const char* law, auto& s) {
        s.sim->set_body_velocity(s.box.body, Vec3(0.005, 0.003, 0), Vec3::Zero(), s.com());
        s.sim->run_until(1.0);
        const Vec3 c1 = s.com();
        double late = 0;
        s.sim->run_until(10.0, [&](const auto& sim, const StepInfo&) {
          if (sim.time() > 9.0) late = std::max(late, max_speed(sim, s.box.body));
        });
        const Vec3 d = s.com() - c1;
        const double drift = std::hypot(d.x(), d.y());
        report("H1 rest, %s box, %s, %s: drift 1-10 s %.2e m, max nodal speed in the last second %.2e m/s", label,
               rigid ? "rigid" : "FE", law, drift, late);
        INFO(law << (rigid ? " rigid " : " FE ") << label);
        CHECK(drift < 1e-4);
        // stiff's dashpots, twice critical for tall items' rocking (stiff_contact.hpp), clamp at zero
        // force when their pull exceeds the spring's push; with that status left to the next step the
        // FE boxes chattered at 1.4 and 2.4 mm/s. Resolved within the step
        // (SimulationOptions::contact_iterations): below 1e-15 m/s.
        CHECK(late < 1e-3);
      });
}

TEST_CASE("a finer frame rests where the iterated equilibrium rests", "[contact_dynamics][rest][implicit]") {
  // H1's tall box with 50 mm elements (34 floor nodes), stiff law, pushed at (5, 3) mm/s: with the
  // dashpot clamp's status left to the next step it chattered at 8.2 mm/s and sat 17 um (seven static
  // deflections of its 2.5 um springs) below the rest of the same frame iterated to equilibrium at
  // every step, whatever the factorisation. Both refresh intervals the scenes use (1, 100 steps).
  const BoxSpec fine_box{0.45, 0.4, 1.2, Vec3::Zero(), 0, 0.05};
  const auto rest = [&](const Newmark& integrator, int refresh) {
    SimulationOptions o = options_dt(1e-3);
    o.refresh_interval_steps = refresh;
    BlockScene<SpringDashpotLaw> s(fine_box, [&](const Box& b) { return stiff(b, 0.3); }, false, o, integrator);
    s.sim->set_body_velocity(s.box.body, Vec3(0.005, 0.003, 0), Vec3::Zero(), s.com());
    s.sim->run_until(2.0);
    double z = 0, late = 0;
    long n = 0;
    s.sim->run_until(3.0, [&](const auto& sim, const StepInfo&) {
      late = std::max(late, max_speed(sim, s.box.body));
      z += centre_of_mass(sim, s.box.body).z();
      ++n;
    });
    return std::pair{z / n, late};
  };
  const auto [z_ref, late_ref] = rest(Newmark::paper(EquilibriumMode::iterate), 1);
  for (const int refresh : {1, 100}) {
    const auto [z, late] = rest(paper_newmark, refresh);
    report("H1 rest, fine FE box (50 mm elements), stiff, refresh %d: max nodal speed in the last second %.2e m/s, "
           "mean height against the iterated rest %+.2e m (its speed %.2e m/s)",
           refresh, late, z - z_ref, late_ref);
    INFO("refresh " << refresh);
    CHECK(late < 1e-3);
    CHECK(std::abs(z - z_ref) < 1e-6);  // within half a static deflection of the springs
  }
}

TEST_CASE("held by 0.9 mu g for 10 s, no law creeps", "[contact_dynamics][friction][implicit]") {
  // Table acceleration ramped to 0.9 mu g over 0.5 s (the tangential modes are far faster), then held
  // 10 s. The elastic step (the stick springs' deflection) is taken 1 s into the hold; the creep is
  // what the block moves after it: at most 0.1 mm. mu 0.2 and 0.5.
  for (const double mu : {0.2, 0.5})
    for (const bool rigid : {true, false})
      for_every_law(small_box, rigid, mu, [&](const char* law, auto& s) {
        s.sim->run_until(0.3);
        const double t0 = s.sim->time(), A = 0.9 * mu * g0;
        s.sim->set_table_acceleration([=](double t) { return Vec3(A * std::clamp((t - t0) / 0.5, 0.0, 1.0), 0, 0); });
        const double x0 = s.com().x();
        s.sim->run_until(t0 + 1.5);
        const double x_elastic = s.com().x() - x0;
        s.sim->run_until(t0 + 10.5);
        const double creep = s.com().x() - x0 - x_elastic;
        report("H2 held at 0.9 mu g, mu %.1f, %s, %s: elastic step %.3e m, creep over 9 s %.3e m", mu,
               rigid ? "rigid" : "FE", law, x_elastic, creep);
        INFO(law << (rigid ? " rigid" : " FE") << " mu " << mu);
        CHECK(std::abs(x_elastic) < 2e-3);
        // The 0.1 mm: the stiff springs creep by round-off (1e-16 m); the paper's soft penalty
        // (3.6 % of L at rest) shares the load unevenly while the block leans, and its lightly loaded
        // contacts slip: 45 um at mu 0.2, 109 um at mu 0.5 measured (stick_slip, on the same penalty:
        // 48 and 129 um). Bound: 0.1 mm except the laws with the paper's penalty at mu 0.5 (0.15 mm),
        // a gap docs/contact/verification_contact.md reports.
        const bool paper = std::string_view(law).starts_with("paper") || std::string_view(law) == "stick_slip";
        CHECK(std::abs(creep) < (paper && mu > 0.3 ? 1.5e-4 : 1e-4));
      });
}

TEST_CASE("harmonic sliding matches an exact Coulomb block to 1 %", "[contact_dynamics][friction][implicit]") {
  // a(t) = r mu g sin(2 pi f t), r from 1.5 to 4 (continuous sliding), f = 2 Hz, mu 0.2 and 0.4; the
  // stiff parameters (sticking friction on the total normal force, the 1-DOF block's), the rigid block
  // and (one case) the FE block. Peak-to-peak slide over the fourth period against the exact
  // integration (coulomb_peak_to_peak, converged to 1e-6 in dt). Measured -0.04 to +0.63 % rigid,
  // +0.80 % FE, with the stick spring critically damped (contact_laws.hpp, stick_spring); undamped it
  // was +0.55 to +1.34 % and +1.95 %.
  struct Case {
    double r, mu;
    bool rigid;
  };
  const double f = 2.0, w = 2 * std::numbers::pi * f;
  for (const Case c : {Case{1.5, 0.2, true}, Case{2.5, 0.4, true}, Case{4.0, 0.2, true}, Case{2.5, 0.2, false}}) {
    BlockScene<SpringDashpotLaw> s(small_box, [&](const Box& b) { return stiff(b, c.mu); }, c.rigid, options_dt(1e-3),
                                   paper_newmark);
    s.sim->run_until(0.3);
    const double t0 = s.sim->time(), A = c.r * c.mu * g0;
    s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 ? A * std::sin(w * (t - t0)) : 0.0, 0, 0); });
    const double x0 = s.com().x();
    double lo = 1e300, hi = -1e300;
    s.sim->run_until(t0 + 4 / f, [&](const auto& sim, const StepInfo&) {
      if (sim.time() < t0 + 3 / f) return;
      const double x = centre_of_mass(sim, s.box.body).x() - x0;
      lo = std::min(lo, x), hi = std::max(hi, x);
    });
    const double closed = coulomb_peak_to_peak(A, w, c.mu, 4);
    report("H3 harmonic sliding r %.1f, mu %.1f, %s: peak-to-peak %.5f m, exact 1-DOF %.5f m (%+.2f%%)", c.r, c.mu,
           c.rigid ? "rigid" : "FE", hi - lo, closed, 100 * ((hi - lo) / closed - 1));
    CHECK_THAT(hi - lo, Catch::Matchers::WithinRel(closed, 0.01));
  }
}

TEST_CASE("a suddenly applied constant acceleration above g b/h overturns a block", "[contact_dynamics][rocking][implicit]") {
  // A rigid block on rigid ground tips under a held table acceleration a exactly when a > g b/h (b half
  // the footprint along x, h the height of the centre of mass above the pivot line, here the bottom
  // nodes' centre line): below it the restoring moment wins at once. Applied suddenly, a compliant
  // contact overshoots and lifts the heel early (4 to 5 % below g b/h with the paper's soft penalty);
  // the stiff parameters keep that within 1 % (rigid). A frame is flexible: suddenly loaded, its sway
  // adds to the rocking, so it may tip a little below g b/h; at 2 % below, its reference is the same
  // frame with the paper's Newmark iterated to equilibrium at every step (factorised every step, every
  // contact at every iterate), which no contact-status scheme can bias. Friction mu = 2 b/h: no sliding.
  const BoxSpec medium_box{0.4, 0.3, 0.8, Vec3::Zero(), 0, 0.05};
  struct Rise {
    double largest = 0, last = 0;  // m: the highest edge above its resting height, at most and at the end
  };
  const auto sudden_rise = [](const BoxSpec& box, bool rigid, double level, const Newmark& integrator) {
    const double mu = 2 * 0.5 * box.bx / (0.5 * box.h);  // twice b/h: it tips before it slides
    BlockScene<SpringDashpotLaw> s(box, [&](const Box& b) { return stiff(b, mu); }, rigid, options_dt(1e-3), integrator);
    s.sim->run_until(0.3);
    const double b_over_h = 0.5 * box.bx / (s.box.cog.z() - tube_half_width);
    const double t0 = s.sim->time(), A = level * g0 * b_over_h;
    s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 ? A : 0.0, 0, 0); });
    Rise r;
    s.sim->run_until(t0 + 2.0, [&](const auto& sim, const StepInfo&) {
      r.last = std::max(mean_z(sim, s.box.heel), mean_z(sim, s.box.toe)) - tube_half_width;
      r.largest = std::max(r.largest, r.last);
    });
    return std::pair{r, b_over_h};
  };
  for (const auto& [box, label] : {std::pair{medium_box, "medium"}, std::pair{tall_box, "tall"}})
    for (const bool rigid : {true, false})
      for (const double level : rigid ? std::vector{0.99, 1.01} : std::vector{0.96, 0.98, 1.02}) {
        const auto [rise, b_over_h] = sudden_rise(box, rigid, level, paper_newmark);
        report("H4 sudden constant acceleration %.2f g b/h (b/h %.4f), %s box, %s: largest edge rise %.3e m, at 2 s %.3e m",
               level, b_over_h, label, rigid ? "rigid" : "FE", rise.largest, rise.last);
        INFO(label << (rigid ? " rigid" : " FE") << " level " << level);
        // The edge rise at which the centre of mass is over the pivot: past it the block falls.
        const double tipping_rise = box.bx * b_over_h / std::sqrt(1 + b_over_h * b_over_h);
        if (level > 1) {
          CHECK(rise.largest > 0.05);
          CHECK(rise.last > tipping_rise);
        } else if (rigid || level < 0.97) {
          // It may lift elastically (it stands on 2.5 um springs) but falls back: a rise of 1 cm
          // would be a rocking excursion.
          CHECK(rise.largest < 0.01);
          CHECK(rise.last < 1e-3);
        } else {
          // Within 2 % of g b/h the frame's sway decides: the tall frame's toe rises past the unstable
          // equilibrium (3 mm at 0.98 g b/h for a rigid block) and it tips over at 2.7 s. Its largest
          // rise as the iterated reference's, within 10 % and 1 mm (measured: medium 0.827 against
          // 0.827 mm, tall 59.74 against 59.80 mm; with the dashpot clamp's status left to the next
          // step, the tall frame's chatter damped its sway: 2.2 mm).
          const auto [reference, unused] = sudden_rise(box, false, level, Newmark::paper(EquilibriumMode::iterate));
          report("H4 the same frame iterated to equilibrium at every step: largest edge rise %.3e m, at 2 s %.3e m",
                 reference.largest, reference.last);
          CHECK(std::abs(rise.largest - reference.largest) < 0.1 * reference.largest + 1e-3);
          CHECK(std::abs(rise.last - reference.last) < 0.1 * reference.last + 1e-3);
        }
      }
}

TEST_CASE("a frame's reused factorisation tips it as one refactorised every step", "[contact_dynamics][rocking][implicit][refresh]") {
  // Scenes reuse a flexible body's factorisation for 0.1 s (refresh_every) and put contact changes on
  // it by a low-rank update, or, when more than 16 nodes change at once (a tipping frame's heel lifting
  // off), factorise it in the same step. That factorisation took the matrix as last factorised, its
  // contact terms included, and added the new terms to it: each such refresh stacked another set of
  // floor springs (and kept the structure of the old configuration). A tall frame under 1.5 g b/h,
  // stiff law, mu = 2 b/h, then stalled on its edge (the furniture kind tall_cabinet at 2.4 g b/h: 7 deg
  // in 3 s instead of overturning; at 1.02 g b/h it diverged). Exact would be the same motion as with
  // a factorisation at every step (SimulationOptions' default), to the solver's modified-Newton error.
  std::vector<Vec3> path[2];
  for (const int interval : {1, 100}) {
    SimulationOptions o = options_dt(1e-3);
    o.refresh_interval_steps = interval;
    const double mu = 2 * 0.5 * tall_box.bx / (0.5 * tall_box.h);
    BlockScene<SpringDashpotLaw> s(tall_box, [&](const Box& b) { return stiff(b, mu); }, false, o, paper_newmark);
    s.sim->run_until(0.3);
    const double b_over_h = 0.5 * tall_box.bx / (s.box.cog.z() - tube_half_width);
    const double t0 = s.sim->time(), A = 1.5 * g0 * b_over_h;
    s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 ? A : 0.0, 0, 0); });
    auto& p = path[interval == 1 ? 0 : 1];
    long step = 0;
    s.sim->run_until(t0 + 0.8, [&](const auto&, const StepInfo&) {
      if (++step % 10 == 0) p.push_back(s.com());
    });
  }
  REQUIRE(path[0].size() == path[1].size());
  double largest = 0, travel = 0;
  for (size_t k = 0; k < path[0].size(); ++k) {
    largest = std::max(largest, (path[1][k] - path[0][k]).norm());
    travel = std::max(travel, (path[0][k] - path[0].front()).norm());
  }
  report("H4b tall FE frame, 1.5 g b/h, stiff: centre of mass moved %.3f m in 0.8 s; reused factorisation "
         "(100 steps) against one per step: largest difference %.2e m",
         travel, largest);
  CHECK(travel > 0.1);          // it tips: the centre of mass travels decimetres
  CHECK(largest < 0.02 * travel);  // and the reuse follows the exact path within 2 % of that
}


TEST_CASE("a frame's reused factorisation slides it as one refactorised every step", "[contact_dynamics][friction][implicit][refresh]") {
  // A flexible frame (the small box, 50 mm elements, stiff law, mu 0.3) settles for 0.3 s, then the
  // table accelerates at 0.6 g along +X: its friction goes from stick to slip on every bottom node while
  // the normal part of each node's contact term hardly changes. Between refreshes a node's term entered
  // the Woodbury update only when the whole term changed by 30 % of its norm; a slipping node's slope
  // (friction's secant, falling as it speeds up) never did, and the stale slopes held the frame back
  // (ed5bc2d, 0.5 s: 0.284 m at 10 steps, 0.011 m at 100, against 0.367 m refactorised every step). Now
  // a change of contact regime always enters the step (with that alone: the same numbers), and so does
  // any change of a slipping node's tangential slope (a 30 % tolerance on it: 0.328 m and 0.235 m). Closed form:
  // x = (a - mu g) t^2 / 2 = 0.3677 m at 0.5 s (the FE frame's sway adds little); measured 0.36747 m at
  // every interval. Bounds: 2 % against the closed form, 0.5 % between the intervals (issue 52).
  const double mu = 0.3, a = 0.6 * g0, T = 0.5;
  double slide[3] = {0, 0, 0}, reuse_error[3] = {0, 0, 0};
  int k = 0;
  for (const int interval : {1, 10, 100}) {
    SimulationOptions o = options_dt(1e-3);
    o.refresh_interval_steps = interval;
    BlockScene<SpringDashpotLaw> s(small_box, [&](const Box& b) { return stiff(b, mu); }, false, o, paper_newmark);
    s.sim->run_until(0.3);
    const double t0 = s.sim->time(), x0 = s.com().x();
    s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 ? a : 0.0, 0, 0); });
    s.sim->run_until(t0 + T);
    reuse_error[k] = s.sim->factor_reuse_error();
    slide[k++] = x0 - s.com().x();  // the table pulls forward: the frame slides back relative to it
  }
  const double closed = 0.5 * (a - mu * g0) * T * T;
  report("H5 FE frame sliding at 2 mu g, stiff: slide in %.1f s %.5f / %.5f / %.5f m refreshed every 1 / 10 / 100 "
         "steps, closed form %.5f m",
         T, slide[0], slide[1], slide[2], closed);
  report("H5 factor-reuse error (largest relative change of a contact term left out): %.3f / %.3f / %.3f",
         reuse_error[0], reuse_error[1], reuse_error[2]);
  // What a reused factorisation leaves out stays within the change tolerance (and is reported).
  for (const double e : reuse_error) CHECK(e <= 0.3);
  CHECK(reuse_error[2] > 0);
  CHECK_THAT(slide[0], Catch::Matchers::WithinRel(closed, 0.02));
  CHECK_THAT(slide[1], Catch::Matchers::WithinRel(slide[0], 0.005));
  CHECK_THAT(slide[2], Catch::Matchers::WithinRel(slide[0], 0.005));
}

TEST_CASE("a reused factorisation refines small contact changes: the same slide with fewer factorisations",
          "[contact_dynamics][friction][implicit][refresh]") {
  // H5's sliding frame (factorisation reused for 100 steps): every bottom node slips and its slope
  // changes at every step, more than the 16 nodes a Woodbury update takes, so without refinement the
  // frame is factorised at almost every step. Each change is at most mu g beta dt^2 / stick_length
  // (0.13 here) of its node's diagonal, so conjugate gradients preconditioned by the old factor solve the
  // changed system (SimulationOptions::contact_refinement). Exact is the motion refactorised every step:
  // both ways within 0.5 % of it (H5's bound), and with refinement fewer factorisations.
  const double mu = 0.3, a = 0.6 * g0, T = 0.5;
  struct Run {
    double slide;
    long factorizations, refinement_solves;
  };
  const auto run = [&](int interval, bool refinement) {
    SimulationOptions o = options_dt(1e-3);
    o.refresh_interval_steps = interval;
    o.contact_refinement = refinement;
    BlockScene<SpringDashpotLaw> s(small_box, [&](const Box& b) { return stiff(b, mu); }, false, o, paper_newmark);
    s.sim->run_until(0.3);
    const double t0 = s.sim->time(), x0 = s.com().x();
    const long f0 = s.sim->factorizations();
    s.sim->set_table_acceleration([=](double t) { return Vec3(t > t0 ? a : 0.0, 0, 0); });
    s.sim->run_until(t0 + T);
    return Run{x0 - s.com().x(), s.sim->factorizations() - f0, s.sim->refinement_solves()};
  };
  const Run exact = run(1, false), refined = run(100, true), updated = run(100, false);
  report("H5b sliding frame reused for 100 steps: slide %.5f m refined (%ld factorisations, %ld CG solves), "
         "%.5f m without (%ld factorisations); every step %.5f m",
         refined.slide, refined.factorizations, refined.refinement_solves, updated.slide, updated.factorizations,
         exact.slide);
  CHECK_THAT(refined.slide, Catch::Matchers::WithinRel(exact.slide, 0.005));
  CHECK_THAT(updated.slide, Catch::Matchers::WithinRel(exact.slide, 0.005));
  CHECK(refined.refinement_solves > 0);
  CHECK(updated.refinement_solves == 0);
  CHECK(refined.factorizations < updated.factorizations);
}

}  // namespace holding_still_tests
