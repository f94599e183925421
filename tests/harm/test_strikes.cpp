// Strikes on an occupant (harm/strike.hpp, harm/impact_form.hpp) against closed forms: a box dropped on
// a head, a box pushed into a body at constant speed, HIC of pulses whose value is known.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <sstream>

#include <furniture_fem/core/checkpoint.hpp>
#include <furniture_fem/harm/strike.hpp>

using namespace furniture_fem;

namespace {
constexpr double g = 9.81;

OrientedBox cube_at(const Vec3& centre, double half) {
  OrientedBox b;
  b.centre = centre;
  b.half = Vec3::Constant(half);
  return b;
}

// The relative coordinate y = d - x of a free mass m on a spring k pushed by a wall that starts at
// speed v0 and accelerates at a: m y'' = m a - k y, y(0) = 0, y'(0) = v0 (the closed form).
struct PushedForm {
  double m, k, v0, a;
  double w() const { return std::sqrt(k / m); }
  double y(double t) const { return a / (w() * w()) * (1 - std::cos(w() * t)) + v0 / w() * std::sin(w() * t); }
  double y_max() const {
    const double A = a / (w() * w()), B = v0 / w();
    return A + std::hypot(A, B);
  }
  // When the spring is unloaded again (y back to 0 after its peak), by bisection on (peak, 2 pi / w).
  double end() const {
    double lo = (std::numbers::pi - std::atan(v0 * w() / std::max(a, 1e-300))) / w(), hi = 2 * std::numbers::pi / w();
    if (a == 0) lo = 0.5 * std::numbers::pi / w();
    for (int i = 0; i < 200; ++i) ((y(0.5 * (lo + hi)) > 0) ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  }
  // The spring's impulse to the end: k times the integral of y.
  double impulse() const {
    const double t = end(), W = w();
    return k * (a / (W * W) * (t - std::sin(W * t) / W) + v0 / (W * W) * (1 - std::cos(W * t)));
  }
  // HIC15 of the acceleration k y / m (in standard g), by brute force on a 2 microsecond grid.
  double hic15() const {
    const double h = 2e-6, T = end();
    const int n = static_cast<int>(T / h) + 1;
    std::vector<double> I(n + 1, 0.0);
    for (int i = 1; i <= n; ++i) I[i] = I[i - 1] + h * k * y((i - 0.5) * h) / m / standard_gravity;  // midpoint
    const int span = static_cast<int>(0.015 / h);
    double best = 0;
    for (int i = 0; i <= n; ++i)
      for (int j = i + 1; j <= n && j - i <= span; j += 1) {
        const double T12 = (j - i) * h;
        best = std::max(best, T12 * std::pow((I[j] - I[i]) / T12, 2.5));
      }
    return best;
  }
};
}  // namespace

TEST_CASE("A box dropped on a head: onset, speed and energy of free fall, force and impulse of the pushed form",
          "[harm][strike]") {
  struct Case {
    double mass, half, drop, head_mass, stiffness;
  };
  // Items from a 5 kg box to a 60 kg one, drops of 0.1 to 1.0 m, head forms stiff and soft.
  const Case cases[] = {{20.0, 0.2, 0.5, 4.5, 1.0e6}, {5.0, 0.15, 0.1, 4.5, 1.0e6}, {60.0, 0.25, 1.0, 4.5, 5.0e5},
                        {20.0, 0.2, 0.3, 3.5, 2.0e6}};
  for (const Case& c : cases) {
    Occupant o;
    o.name = "reader";
    o.position = Vec2(1.0, -0.5);
    o.head = ImpactForm{c.head_mass, c.stiffness};
    const Vec3 head = o.head_centre();
    const double top = head.z() + o.head_radius;  // the head's top: the box's bottom reaches it after the drop
    StrikeWatch watch(o, OccupantZone::head, "box");
    const double dt = 1e-3;
    std::optional<Strike> s;
    for (int i = 0; i < 2000 && !s; ++i) {
      const double t = i * dt;
      const Vec3 centre(head.x(), head.y(), top + c.drop + c.half - 0.5 * g * t * t);
      s = watch.observe(t, cube_at(centre, c.half), 0.5 * c.mass * g * g * t * t);
    }
    REQUIRE(s);
    INFO("mass " << c.mass << " kg, drop " << c.drop << " m, head form " << c.head_mass << " kg, " << c.stiffness << " N/m");
    const double t_hit = std::sqrt(2 * c.drop / g), v = g * t_hit;
    CHECK(s->item == "box");
    CHECK(s->zone == OccupantZone::head);
    // The onset interpolated between steps of a quadratic fall: off by at most g dt^2 / (8 v).
    CHECK(s->time == Approx(t_hit).margin(g * dt * dt / (8 * v) + 1e-12));
    // The intrusion rate is the secant over the step of the onset: within g dt of the speed.
    CHECK(s->relative_speed == Approx(v).margin(g * dt));
    // Free fall's energy, interpolated in time: within M g^2 dt^2 of it.
    CHECK(s->kinetic_energy == Approx(c.mass * g * c.drop).margin(c.mass * g * g * dt * dt));
    // The form pushed by the falling box (speed v at onset, accelerating at g): the intrusion is linear
    // between steps (its rate off by g dt / 2 at most) and the form integrated on T/200: 0.5 %.
    const PushedForm f{c.head_mass, c.stiffness, v, g};
    CHECK(s->peak_force == Approx(c.stiffness * f.y_max()).epsilon(0.005));
    CHECK(s->impulse == Approx(f.impulse()).epsilon(0.005));
    CHECK(s->duration == Approx(f.end()).epsilon(0.01));  // to the sub-step (T/200) where contact ended
    CHECK(s->hic15 == Approx(f.hic15()).epsilon(0.01));
    // The verdict follows the thresholds.
    const StrikeThresholds th;
    CHECK((s->kinetic_energy >= th.energy) == (std::find(s->exceeded.begin(), s->exceeded.end(), "energy") != s->exceeded.end()));
    CHECK((s->peak_force >= th.head_force) ==
          (std::find(s->exceeded.begin(), s->exceeded.end(), "head_force") != s->exceeded.end()));
  }
}

TEST_CASE("A box pushed into a body at constant speed: the form leaves at twice the speed", "[harm][strike]") {
  for (const double speed : {0.5, 1.5, 4.0}) {
    Occupant o;
    o.name = "walker";
    o.body = ImpactForm{35.0, 1.0e5};
    StrikeWatch watch(o, OccupantZone::body, "cabinet");
    // A 0.4 m cube at body height moving along +x towards the body's axis (x = 0), 0.5 m away at t = 0.
    const double dt = 2e-3, half = 0.2, gap = 0.5;
    std::optional<Strike> s;
    for (int i = 0; i < 5000 && !s; ++i) {
      const double t = i * dt;
      const Vec3 centre(-(o.body_radius + gap + half) + speed * t, 0.0, 0.9);
      s = watch.observe(t, cube_at(centre, half), 0.5 * 80.0 * speed * speed);
    }
    REQUIRE(s);
    INFO("speed " << speed << " m/s");
    const double m = o.body.mass, k = o.body.stiffness;
    CHECK(s->time == Approx(gap / speed).margin(1e-9));
    CHECK(s->relative_speed == Approx(speed).epsilon(1e-9));
    CHECK(s->peak_force == Approx(speed * std::sqrt(k * m)).epsilon(1e-3));
    CHECK(s->impulse == Approx(2 * m * speed).epsilon(1e-3));
    CHECK(s->hic15 == 0.0);  // HIC is the head's
    CHECK(s->kinetic_energy == Approx(40.0 * speed * speed));
  }
}

TEST_CASE("A box passing beside a head strikes nothing; one resting in the zone strikes once", "[harm][strike]") {
  Occupant o;
  o.name = "reader";
  const Vec3 head = o.head_centre();
  StrikeWatch beside(o, OccupantZone::head, "box");
  StrikeWatch onto(o, OccupantZone::head, "box");
  int strikes_beside = 0, strikes_onto = 0;
  for (int i = 0; i < 400; ++i) {
    const double t = i * 1e-3, z = head.z() + 0.5 - std::min(t, 0.3) * 2.0;  // down 0.6 m at 2 m/s, then at rest
    // 1 mm clear of the head's side all the way down.
    if (beside.observe(t, cube_at(Vec3(head.x() + o.head_radius + 0.2 + 0.001, head.y(), z), 0.2), 10.0)) ++strikes_beside;
    if (onto.observe(t, cube_at(Vec3(head.x(), head.y(), z + 0.3), 0.2), 10.0)) ++strikes_onto;
  }
  if (onto.finish()) ++strikes_onto;
  CHECK(strikes_beside == 0);
  CHECK(!beside.touching());
  CHECK(strikes_onto == 1);
  CHECK(onto.touching());  // it came to rest 0.1 m into the head zone: in contact at the end
  CHECK(onto.intrusion() == Approx(0.1).epsilon(1e-9));  // its face 0.1 m into the 0.1 m head: at the centre
}

TEST_CASE("HIC of pulses with known values", "[harm][hic]") {
  // A square pulse of 100 g for 10 ms: HIC = 0.010 * 100^2.5 = 1000 (the whole pulse is the window).
  std::vector<double> t, a;
  for (int i = 0; i <= 1000; ++i) t.push_back(i * 1e-5), a.push_back(100.0);
  CHECK(head_injury_criterion(t, a, 0.015) == Approx(1000.0).epsilon(1e-9));
  // 30 ms long: the window is capped at 15 ms: 0.015 * 100^2.5 = 1500.
  t.clear(), a.clear();
  for (int i = 0; i <= 3000; ++i) t.push_back(i * 1e-5), a.push_back(100.0);
  CHECK(head_injury_criterion(t, a, 0.015) == Approx(1500.0).epsilon(1e-9));
  CHECK(head_injury_criterion(t, a, 0.036) == Approx(0.030 * std::pow(100.0, 2.5)).epsilon(1e-9));
}

TEST_CASE("A capsule's distance to a box", "[harm][geometry]") {
  Occupant o;  // standing at the origin: body axis from z = 0.2 to 1.30
  const OrientedBox box = cube_at(Vec3(1.0, 0.0, 0.5), 0.25);  // faces at x = 0.75, z from 0.25 to 0.75
  CHECK(zone_intrusion(o, OccupantZone::body, box) == Approx(o.body_radius - 0.75).epsilon(1e-9));
  const OrientedBox above = cube_at(Vec3(0.0, 0.0, 2.5), 0.25);  // bottom face at z = 2.25
  CHECK(zone_intrusion(o, OccupantZone::head, above) == Approx(o.head_radius - (2.25 - o.head_centre().z())).epsilon(1e-9));
  CHECK(zone_intrusion(o, OccupantZone::body, above) == Approx(o.body_radius - (2.25 - o.body_top().z())).epsilon(1e-9));
}

TEST_CASE("A watch saved in the middle of a strike and loaded into a new one finishes it as the first would",
          "[harm][strike][checkpoint]") {
  Occupant o;
  o.name = "reader";
  const Vec3 head = o.head_centre();
  const auto box_at = [&](double t) { return cube_at(Vec3(head.x(), head.y(), head.z() + o.head_radius + 0.5 + 0.2 - 0.5 * g * t * t), 0.2); };
  const double dt = 1e-3;
  StrikeWatch whole(o, OccupantZone::head, "box");
  std::optional<Strike> expected;
  for (int i = 0; i < 2000 && !expected; ++i) expected = whole.observe(i * dt, box_at(i * dt), 1.0 * i);
  REQUIRE(expected);
  // Again, saved two steps after the onset (the form in contact) and resumed in a new watch.
  const int onset_step = static_cast<int>(std::ceil(expected->time / dt));
  StrikeWatch first(o, OccupantZone::head, "box");
  for (int i = 0; i <= onset_step + 1; ++i) REQUIRE_FALSE(first.observe(i * dt, box_at(i * dt), 1.0 * i));
  StateWriter w;
  w(first);
  const std::string bytes = w.bytes();
  StrikeWatch second(o, OccupantZone::head, "box");
  StateReader r(bytes, "watch");
  r(second);
  r.finish();
  std::optional<Strike> resumed;
  for (int i = onset_step + 2; i < 2000 && !resumed; ++i) resumed = second.observe(i * dt, box_at(i * dt), 1.0 * i);
  REQUIRE(resumed);
  CHECK(resumed->time == expected->time);
  CHECK(resumed->kinetic_energy == expected->kinetic_energy);
  CHECK(resumed->peak_force == expected->peak_force);
  CHECK(resumed->impulse == expected->impulse);
  CHECK(resumed->hic15 == expected->hic15);
  CHECK(resumed->duration == expected->duration);
  CHECK(resumed->exceeded == expected->exceeded);
}

TEST_CASE("An item leaning on a person strikes again when it falls through, at its falling speed", "[harm][strike]") {
  // A box creeps 3 cm into a body's zone at 2 cm/s (one slow strike), rocks there by 5 mm (no strike:
  // never deeper than before), then moves on at 2 m/s: a second strike, at 2 m/s, whose form sees the
  // intrusion beyond the 3 cm it had reached (peak v sqrt(k m), impulse 2 m v as from outside).
  Occupant o;
  o.name = "walker";
  StrikeWatch watch(o, OccupantZone::body, "cabinet");
  const double dt = 1e-3, half = 0.2, x0 = -(o.body_radius + half);  // the box's face at the zone's surface
  std::vector<Strike> strikes;
  double x = x0 - 0.01, t = 0;
  const auto step = [&](double dx) {
    x += dx, t += dt;
    if (auto s = watch.observe(t, cube_at(Vec3(x, 0.0, 0.9), half), 10.0)) strikes.push_back(*s);
  };
  for (int i = 0; i < 2000; ++i) step(0.02 * dt);                                            // to 3 cm in
  for (int i = 0; i < 1000; ++i) step((i / 100) % 2 == 0 ? -0.5e-4 : 0.5e-4);               // rocks by 5 mm
  for (int i = 0; i < 200; ++i) step(2.0 * dt);                                              // through
  if (auto s = watch.finish()) strikes.push_back(*s);
  REQUIRE(strikes.size() == 2);
  CHECK(strikes[0].relative_speed == Approx(0.02).epsilon(1e-6));
  CHECK(strikes[1].relative_speed == Approx(2.0).epsilon(1e-6));
  CHECK(strikes[1].time == Approx(3.0).margin(2 * dt));
  const double m = o.body.mass, k = o.body.stiffness;
  CHECK(strikes[1].peak_force == Approx(2.0 * std::sqrt(k * m)).epsilon(1e-3));
  CHECK(strikes[1].impulse == Approx(2 * m * 2.0).epsilon(1e-3));
}

TEST_CASE("A segment's exact distance to a box agrees with a search along it", "[harm][geometry]") {
  // 2000 boxes turned at random and segments at random, apart and crossing: the closed form on each
  // piece against golden-section search on the signed distance (its own tolerance 1e-9 of the length).
  std::srand(7);
  const auto u = [] { return 2.0 * std::rand() / RAND_MAX - 1.0; };
  int apart = 0;
  for (int i = 0; i < 2000; ++i) {
    OrientedBox box;
    box.centre = Vec3(u(), u(), u());
    box.axes = Eigen::Quaterniond(Eigen::Vector4d(u(), u(), u(), u()).normalized()).toRotationMatrix();
    box.half = Vec3(0.05 + 0.5 * std::abs(u()), 0.05 + 0.5 * std::abs(u()), 0.05 + std::abs(u()));
    const Vec3 p(2 * u(), 2 * u(), 2 * u()), q(2 * u(), 2 * u(), 2 * u());
    const double search = detail::segment_box_signed_distance_search(p, q, box);
    const double exact = detail::segment_box_distance(p, q, box);
    apart += search > 0;
    INFO("case " << i);
    CHECK(exact == Approx(search).margin(1e-8));
  }
  CHECK(apart > 500);  // both kinds of case were drawn
  CHECK(apart < 1900);
}

TEST_CASE("A person standing as an obstacle: a strike is the contact force it carries", "[harm][strike][obstacle]") {
  // A box approaching a head at 1 m/s meets it at step 50: the contact pushes 6 kN for 100 steps of 0.1 ms,
  // then none. One strike, half a step before the first force; peak 6 kN; impulse the trapezoid of the
  // samples (0 at the onset, 6 kN half a step later and for 99 steps more, 0 a step after: 99.75 steps of
  // 6 kN); HIC15 of 6 kN / 4.5 kg over its 10 ms against the square pulse's T (F / m g)^2.5 within 2 %
  // (the ramps at its ends); above the HIC and the head force thresholds. Then it rests:
  // a contact lost for a step and found at rest is no new strike; after backing away and returning at
  // 0.5 m/s it is a second one; a strike still pushing after `longest` is closed there.
  Occupant o;
  o.name = "guard";
  o.obstacle = true;
  StrikeWatch watch(o, OccupantZone::head, "box");
  const double dt = 1e-4, P = 6000.0;
  std::vector<Strike> strikes;
  double t = 0, d = -0.05;
  const auto step = [&](double v, double F) {
    t += dt, d += v * dt;
    if (auto s = watch.observe_contact(t, d, 3.0, F)) strikes.push_back(*s);
  };
  for (int i = 0; i < 50; ++i) step(1.0, 0.0);
  const double t_first = t + dt;
  for (int i = 0; i < 100; ++i) step(1.0, P);
  step(0.0, 0.0);
  REQUIRE(strikes.size() == 1);
  const Strike& s = strikes[0];
  CHECK(s.time == Approx(t_first - 0.5 * dt).margin(1e-12));
  CHECK(s.relative_speed == Approx(1.0).epsilon(1e-9));
  CHECK(s.kinetic_energy == Approx(3.0));
  CHECK(s.peak_force == P);
  CHECK(s.impulse == Approx(99.75 * dt * P).epsilon(1e-9));
  CHECK(s.duration == Approx(99.5 * dt).epsilon(1e-9));
  CHECK(s.hic15 == Approx(0.01 * std::pow(P / o.head.mass / standard_gravity, 2.5)).epsilon(0.02));
  CHECK(s.exceeded == std::vector<std::string>{"hic15", "head_force"});
  // Resting: the force comes and goes at rest.
  for (int i = 0; i < 100; ++i) step(0.0, i % 7 == 3 ? 0.0 : 50.0);
  CHECK(strikes.size() == 1);
  // Backs away, returns at 0.5 m/s.
  for (int i = 0; i < 100; ++i) step(-0.5, 0.0);
  for (int i = 0; i < 100; ++i) step(0.5, 0.0);
  for (int i = 0; i < 10; ++i) step(0.5, 300.0);
  step(-0.5, 0.0);
  REQUIRE(strikes.size() == 2);
  CHECK(strikes[1].relative_speed == Approx(0.5).epsilon(1e-9));
  CHECK(strikes[1].peak_force == 300.0);
  // Pushing for longer than `longest`: closed there, not opened again while it pushes.
  for (int i = 0; i < 100; ++i) step(-0.5, 0.0);
  for (int i = 0; i < 100; ++i) step(0.5, 0.0);
  for (int i = 0; i < static_cast<int>(1.5 * StrikeWatch::longest / dt); ++i) step(i == 0 ? 0.5 : 0.0, 100.0);
  REQUIRE(strikes.size() == 3);
  CHECK(strikes[2].duration == Approx(StrikeWatch::longest).margin(dt));
  CHECK(watch.touching());
  CHECK_FALSE(watch.finish());
}

TEST_CASE("A person standing as an obstacle against an item from the start is not struck by it", "[harm][strike][obstacle]") {
  // The run's contact forces exist from the first step on (none at t = 0): a seated person whose chair
  // touches them from the start showed a strike at 0.000 s with 0 J. A force from the first step is no
  // strike; once it is gone, the item's return is one.
  Occupant o;
  o.name = "clerk";
  o.obstacle = true;
  StrikeWatch watch(o, OccupantZone::body, "chair");
  const double dt = 1e-3;
  CHECK_FALSE(watch.observe_contact(0.0, -0.001, 0.0, 0.0));  // the initial state: no force evaluated yet
  for (int i = 1; i <= 100; ++i) CHECK_FALSE(watch.observe_contact(i * dt, -0.001, 0.0, 55.0));
  CHECK_FALSE(watch.finish());
  CHECK_FALSE(watch.observe_contact(0.101, -0.01, 0.0, 0.0));  // it moves off
  CHECK_FALSE(watch.observe_contact(0.102, -0.009, 0.5, 80.0));  // and back at 1 m/s: a strike
  const auto s = watch.finish();
  REQUIRE(s);
  CHECK(s->time == Approx(0.1015));
  CHECK(s->relative_speed == Approx(1.0));
}
