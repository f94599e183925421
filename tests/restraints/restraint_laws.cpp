// The restraints' force laws against their definitions in closed form (docs/restraints/restraints.md):
// each kind's force and regime at known displacements, its slope against a central difference of its
// force, and a set's energy (work, stored, dissipated) over a load cycle against the backbone's area.
#include <catch2/catch.hpp>

#include <furniture_fem/restraints/restraint_set.hpp>

using namespace furniture_fem;

namespace {

Restraint placed(RestraintKind kind, const Vec3& normal = Vec3::UnitX(), const Vec3& anchor = Vec3::Zero()) {
  Restraint r;
  r.name = std::string(to_string(kind));
  r.kind = kind;
  r.body = 0;
  r.node = 0;
  r.rest = Vec3(0.1, 0.2, 1.5);
  r.anchor = anchor;
  r.normal = normal;
  r.p = default_restraint_params(kind);
  return r;
}

// The slope by central differences of the force, from the same committed state.
Mat3 slope_by_differences(const Restraint& r, const RestraintState& from, const Vec3& x, double h = 1e-7) {
  Mat3 K;
  for (int j = 0; j < 3; ++j) {
    const Vec3 dx = h * Vec3::Unit(j);
    K.col(j) = -(restraint_response(r, from, x + dx).on_item - restraint_response(r, from, x - dx).on_item) / (2 * h);
  }
  return K;
}

}  // namespace

TEST_CASE("An L-bracket pulls back elastically, yields at its strength, softens and breaks", "[restraints]") {
  for (const double strength : {300.0, 1000.0, 2500.0}) {
    Restraint r = placed(RestraintKind::l_bracket, Vec3(-1, 0, 0));  // a wall at +x: pulling is moving -x
    r.p.strength = strength;
    r.p.softening = 3 * strength / r.p.stiffness;  // valid: a fall less steep than the elastic slope
    const double k = r.p.stiffness, F = strength, S = F / r.p.softening;
    const RestraintState rest = initial_restraint_state(r);
    const auto pulled = [&](double pull, const RestraintState& from) {
      return restraint_response(r, from, r.rest + pull * r.normal);
    };
    // Elastic: F = k pull, back toward the wall.
    const double elastic = 0.5 * F / k;
    RestraintResponse e = pulled(elastic, rest);
    CHECK(e.state.regime == RestraintRegime::elastic);
    CHECK(e.on_item.isApprox(-k * elastic * r.normal, 1e-12));
    CHECK(e.K.isApprox(slope_by_differences(r, rest, e.state.x), 1e-6));
    // On the plateau: the force is the strength, the plastic pull what is beyond F / k.
    const double on_plateau = F / k + 0.5 * r.p.plateau;
    RestraintResponse y = pulled(on_plateau, rest);
    CHECK(y.state.regime == RestraintRegime::yielding);
    CHECK(y.state.force == Approx(F).epsilon(1e-12));
    CHECK(y.state.plastic == Approx(0.5 * r.p.plateau).epsilon(1e-12));
    // Unloaded from there: elastic again about the plastic pull it kept.
    RestraintResponse u = pulled(F / k, y.state);
    CHECK(u.state.regime == RestraintRegime::elastic);
    CHECK(u.state.force == Approx(k * (F / k - 0.5 * r.p.plateau)).epsilon(1e-12));
    // Softening: the force on the falling branch F - S (p - plateau) equals k (pull - p): checked by
    // bisection on p, independent of the return mapping's formula.
    const double soft_pull = r.p.plateau + 0.5 * r.p.softening + F / k;
    RestraintResponse s = pulled(soft_pull, rest);
    double lo = r.p.plateau, hi = r.p.plateau + r.p.softening;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (k * (soft_pull - mid) > F - S * (mid - r.p.plateau) ? lo : hi) = mid;
    }
    CHECK(s.state.regime == RestraintRegime::softening);
    CHECK(s.state.force == Approx(F - S * (lo - r.p.plateau)).epsilon(1e-9));
    // Beyond plateau + softening of plastic pull: broken, and it stays so.
    RestraintResponse b = pulled(r.p.plateau + r.p.softening + F / k + 1e-4, rest);
    CHECK(b.state.broken());
    CHECK(b.state.failure == RestraintFailure::pull_out);
    CHECK(b.on_item.norm() == 0);
    CHECK(pulled(0.0, b.state).on_item.norm() == 0);
  }
}

TEST_CASE("An L-bracket carries shear on its own stiffness and shears off brittle", "[restraints]") {
  Restraint r = placed(RestraintKind::l_bracket, Vec3(0, 1, 0));
  const RestraintState rest = initial_restraint_state(r);
  const Vec3 down(0, 0, -1);
  const double below = 0.9 * r.p.shear_strength / r.p.shear_stiffness;
  const RestraintResponse held = restraint_response(r, rest, r.rest + below * down);
  CHECK(held.on_item.isApprox(-r.p.shear_stiffness * below * down, 1e-12));
  CHECK(held.K.isApprox(slope_by_differences(r, rest, held.state.x), 1e-6));
  const RestraintResponse off = restraint_response(r, rest, r.rest + 1.2 * below / 0.9 * down);
  CHECK(off.state.failure == RestraintFailure::shear);
}

TEST_CASE("A strap is slack until taut, then pulls along itself and breaks at its strength", "[restraints]") {
  for (const double slack : {0.0, 0.01, 0.05}) {
    Restraint r = placed(RestraintKind::strap, Vec3(-1, 0, 0), Vec3(0.4, 0.2, 1.7));
    r.p.slack = slack;
    const RestraintState rest = initial_restraint_state(r);
    const Vec3 away = (r.rest - r.anchor).normalized();
    const double taut = (r.rest - r.anchor).norm() + slack;
    // Moved along the strap by less than the slack: nothing.
    if (slack > 0) CHECK(restraint_response(r, rest, r.anchor + 0.99 * taut * away).state.regime == RestraintRegime::idle);
    // Stretched by e: k e toward the anchor.
    const double e = 0.5 * r.p.strength / r.p.stiffness;
    const Vec3 x = r.anchor + (taut + e) * away;
    const RestraintResponse t = restraint_response(r, rest, x);
    CHECK(t.on_item.isApprox(-r.p.stiffness * e * away, 1e-9));
    // Its slope, geometric part included, off its axis too.
    const Vec3 x_off = x + Vec3(0, 0.03, -0.02);
    CHECK(restraint_response(r, rest, x_off).K.isApprox(slope_by_differences(r, rest, x_off), 1e-5));
    const RestraintResponse broken = restraint_response(r, rest, r.anchor + (taut + 1.01 * r.p.strength / r.p.stiffness) * away);
    CHECK(broken.state.failure == RestraintFailure::tension);
  }
}

TEST_CASE("A mat holds in shear and uplift on its gel and peels off at its strengths", "[restraints]") {
  Restraint r = placed(RestraintKind::mat, Vec3::UnitZ());
  const RestraintState rest = initial_restraint_state(r);
  const double k = r.p.stiffness;
  const Vec3 shear(0.6, 0.8, 0);
  const double s = 0.9 * r.p.strength / k;
  CHECK(restraint_response(r, rest, r.rest + s * shear).on_item.isApprox(-k * s * shear, 1e-12));
  // Pressed down: the floor's contact carries it, not the mat.
  CHECK(restraint_response(r, rest, r.rest - Vec3(0, 0, 1e-3)).on_item.norm() == 0);
  const double lift = 0.9 * r.p.tension_strength / k;
  const RestraintResponse up = restraint_response(r, rest, r.rest + Vec3(0, 0, lift));
  CHECK(up.on_item.isApprox(Vec3(0, 0, -k * lift), 1e-12));
  CHECK(up.K.isApprox(slope_by_differences(r, rest, up.state.x), 1e-6));
  CHECK(restraint_response(r, rest, r.rest + 1.2 * s * shear).state.failure == RestraintFailure::peel);
  CHECK(restraint_response(r, rest, r.rest + Vec3(0, 0, 1.2 * lift)).state.failure == RestraintFailure::uplift);
}

TEST_CASE("A pole presses with its preload, its pad holds up to friction times its force, and it shortens above its strength", "[restraints]") {
  for (const double mu : {0.3, 0.5, 0.8}) {
    Restraint r = placed(RestraintKind::pole, Vec3(0, 0, -1), Vec3(0.1, 0.2, 2.4));
    r.p.friction = mu;
    const RestraintState rest = initial_restraint_state(r);
    CHECK(rest.force == Approx(r.p.preload).epsilon(1e-12));
    CHECK(restraint_response(r, rest, r.rest).on_item.isApprox(Vec3(0, 0, -r.p.preload), 1e-12));
    // Pushed sideways far: the pad slips, the horizontal force is mu N.
    const RestraintResponse far = restraint_response(r, rest, r.rest + Vec3(0.05, 0, 0));
    CHECK(far.state.regime == RestraintRegime::slipping);
    CHECK(far.on_item.x() == Approx(-mu * r.p.preload).epsilon(1e-12));
    // A little: the pad's spring.
    const double small = 0.5 * mu * r.p.preload / r.p.lateral_stiffness;
    const RestraintResponse near = restraint_response(r, rest, r.rest + Vec3(0, small, 0));
    CHECK(near.on_item.y() == Approx(-r.p.lateral_stiffness * small).epsilon(1e-12));
    CHECK(near.K.isApprox(slope_by_differences(r, rest, near.state.x), 1e-6));
    // The item rises: more compression, k per metre.
    const double rise = 1e-3;
    CHECK(restraint_response(r, rest, r.rest + Vec3(0, 0, rise)).state.force ==
          Approx(r.p.preload + r.p.stiffness * rise).epsilon(1e-12));
    // It drops by more than preload / k: the pole lifts off, no force.
    CHECK(restraint_response(r, rest, r.rest - Vec3(0, 0, 1.1 * r.p.preload / r.p.stiffness)).state.regime ==
          RestraintRegime::idle);
  }
  // The lock slips below the board's strength: shortened, it comes back with less preload.
  Restraint r = placed(RestraintKind::pole, Vec3(0, 0, -1), Vec3(0.1, 0.2, 2.4));
  r.p.slip_strength = 500;
  const RestraintState rest = initial_restraint_state(r);
  const double rise = (r.p.slip_strength - r.p.preload) / r.p.stiffness + 1e-3;
  const RestraintResponse slipped = restraint_response(r, rest, r.rest + Vec3(0, 0, rise));
  CHECK(slipped.state.force == Approx(500).epsilon(1e-12));
  CHECK(slipped.state.plastic == Approx(1e-3).epsilon(1e-9));
  CHECK(restraint_response(r, slipped.state, r.rest).state.force == Approx(r.p.preload - r.p.stiffness * 1e-3).epsilon(1e-9));
  // The board crushes below the lock's strength; past board_travel the pad has punched through.
  r.p.slip_strength = 2000;
  const double through = (r.p.board_strength - r.p.preload) / r.p.stiffness + 1.01 * r.p.board_travel;
  CHECK(restraint_response(r, rest, r.rest + Vec3(0, 0, through)).state.failure == RestraintFailure::punch_through);
}

TEST_CASE("A stopper bears the edge from below, holds it sideways up to friction times its force, and is lost crushed or slid off", "[restraints]") {
  for (const double mu : {0.3, 0.5, 0.8}) {
    Restraint r = placed(RestraintKind::stopper, Vec3::UnitZ(), Vec3(0.1, 0.2, 0.0));
    r.p.friction = mu;
    const RestraintState rest = initial_restraint_state(r);
    CHECK(rest.regime == RestraintRegime::idle);  // placed on it: nothing until the edge settles
    // The edge sinks by s: N = k s upward.
    const double sink = 2e-4;
    const RestraintResponse on = restraint_response(r, rest, r.rest - Vec3(0, 0, sink));
    const double N = r.p.stiffness * sink;
    CHECK(on.on_item.isApprox(Vec3(0, 0, N), 1e-12));
    CHECK(on.state.force == Approx(N).epsilon(1e-12));
    CHECK(on.state.stored == Approx(0.5 * N * N / r.p.stiffness).epsilon(1e-12));
    // Sideways a little: the wedge top's spring; far (within its reach): it slips at mu N.
    const double small = 0.5 * mu * N / r.p.lateral_stiffness;
    const RestraintResponse near = restraint_response(r, rest, r.rest + Vec3(small, 0, -sink));
    CHECK(near.on_item.x() == Approx(-r.p.lateral_stiffness * small).epsilon(1e-12));
    CHECK(near.K.isApprox(slope_by_differences(r, rest, near.state.x), 1e-6));
    const RestraintResponse far = restraint_response(r, rest, r.rest + Vec3(0, 0.5 * r.p.reach, -sink));
    CHECK(far.state.regime == RestraintRegime::slipping);
    CHECK(far.on_item.y() == Approx(-mu * N).epsilon(1e-12));
    // Lifted: nothing; and where it lands, it is held from there.
    const RestraintResponse lifted = restraint_response(r, rest, r.rest + Vec3(0.004, 0, 1e-3));
    CHECK(lifted.state.regime == RestraintRegime::idle);
    CHECK(lifted.on_item.isZero());
    const RestraintResponse landed = restraint_response(r, lifted.state, r.rest + Vec3(0.004, 0, -sink));
    CHECK(landed.on_item.isApprox(Vec3(0, 0, N), 1e-12));
  }
  Restraint r = placed(RestraintKind::stopper, Vec3::UnitZ());
  const RestraintState rest = initial_restraint_state(r);
  // Its bearing is damped while it bears: sinking at 1 cm/s adds c v; its slope in v against differences.
  const Vec3 sunk = r.rest - Vec3(0, 0, 2e-4), v(0.002, 0, -0.01);
  const RestraintResponse moving = restraint_response(r, rest, sunk, v);
  CHECK(moving.on_item.z() == Approx(r.p.stiffness * 2e-4 + r.p.damping * 0.01).epsilon(1e-12));
  Mat3 C;
  for (int j = 0; j < 3; ++j) {
    const Vec3 dv = 1e-7 * Vec3::Unit(j);
    C.col(j) = -(restraint_response(r, rest, sunk, v + dv).on_item - restraint_response(r, rest, sunk, v - dv).on_item) / 2e-7;
  }
  CHECK(moving.C.isApprox(C, 1e-6));
  // Leaving faster than the wedge follows: nothing (it does not pull the edge down).
  CHECK(restraint_response(r, rest, sunk, Vec3(0, 0, 1.0)).state.regime == RestraintRegime::idle);
  const double crushing = 1.01 * r.p.strength / r.p.stiffness;
  CHECK(restraint_response(r, rest, r.rest - Vec3(0, 0, crushing)).state.failure == RestraintFailure::crush);
  const RestraintResponse off = restraint_response(r, rest, r.rest + Vec3(1.01 * r.p.reach, 0, -1e-4));
  CHECK(off.state.failure == RestraintFailure::slid_off);
  CHECK(off.on_item.isZero());
  CHECK(restraint_response(r, off.state, r.rest - Vec3(0, 0, 1e-4)).on_item.isZero());  // lost for good
}

TEST_CASE("A restraint set's ledger: the work it took is what it stores plus what it dissipated", "[restraints]") {
  // A bracket pulled past its yield and back to zero force: the dissipated energy is the plateau's
  // area, strength times the plastic pull; nothing stays stored.
  Restraint r = placed(RestraintKind::l_bracket, Vec3(-1, 0, 0));
  RestraintSet set({r});
  const double k = r.p.stiffness, F = r.p.strength, plastic = 0.5 * r.p.plateau;
  // Steps that meet the yield point exactly: the trapezoidal work is then exact on each linear piece.
  const std::vector<double> pulls = {0.5 * F / k, F / k, F / k + 0.5 * plastic, F / k + plastic, 0.5 * F / k + plastic, plastic};
  double t = 0;
  for (double pull : pulls) {
    set.evaluate(0, r.rest + pull * r.normal);
    set.commit(t += 0.01);
  }
  CHECK(set.states()[0].force == Approx(0).margin(1e-9));
  CHECK(set.stored_energy() == Approx(0).margin(1e-12));
  CHECK(set.dissipated_energy() == Approx(F * plastic).epsilon(1e-9));
  CHECK(set.dissipated_energy(0) == Approx(F * plastic).epsilon(1e-9));
  CHECK(set.states()[0].peak_force == Approx(F).epsilon(1e-12));
  // Broken: the break's time is the commit's, and what it stored at the break is dissipated.
  set.evaluate(0, r.rest + (r.p.plateau + r.p.softening + F / k + 0.01) * r.normal);
  set.commit(0.5);
  CHECK(set.states()[0].broke_at == 0.5);
  CHECK(set.states()[0].regime == RestraintRegime::broken);
}

TEST_CASE("A restraint with a value out of its range, or a snapping softening, is refused by name", "[restraints]") {
  Restraint r = placed(RestraintKind::l_bracket);
  r.name = "tc_left";
  r.p.strength = -5;
  CHECK_THROWS_WITH(RestraintSet({r}), Catch::Contains("restraint 'tc_left'") && Catch::Contains("strength = -5"));
  r.p = default_restraint_params(RestraintKind::l_bracket);
  r.p.softening = 0.5 * r.p.strength / r.p.stiffness;
  CHECK_THROWS_WITH(RestraintSet({r}), Catch::Contains("softening"));
  Restraint pole = placed(RestraintKind::pole, Vec3(0, 0, -1));
  pole.p.preload = 700;  // above the board's 600 N
  CHECK_THROWS_WITH(RestraintSet({pole}), Catch::Contains("preload = 700"));
}
