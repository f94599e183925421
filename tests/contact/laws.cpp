// Contact laws: the paper's equations on a hand-computed case, the pair helpers (equal and opposite
// forces, no net torque), a 1-DOF impact against the closed-form restitution, stick-slip against
// creep, anisotropic friction, parameter checks, and two laws compared on the same kinematics.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/contact_laws.hpp>

#include <numbers>
#include <random>

using namespace furniture_fem;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

namespace laws_tests {  // this file's own names (its group compiles files in batches)

namespace {
constexpr double g0 = 9.80665;

ContactKinematics plane_kinematics(double l, double L, const Vec3& v, double dt = 1e-3) {
  ContactKinematics k;
  k.l = l;
  k.L = L;
  k.n = Vec3::UnitZ();
  k.v = v;
  k.dt = dt;
  return k;
}

// A mass m moving along n against a law (no gravity): velocity Verlet with the velocity in the
// damping force predicted at the end of the step. Starts touching (l = L) with speed v0 towards
// the contact and returns the speed when it leaves; peak penetration through *max_overlap.
template <class Law>
double rebound_speed(const Law& law, const ContactParams& p, double m, double v0, double dt, double* max_overlap = nullptr) {
  const double L = 0.05;
  double y = L, v = -v0;
  ContactState st;
  auto accel = [&](double yy, double vv) { return law.force(plane_kinematics(yy, L, Vec3(0, 0, vv), dt), p, st).on_a.z() / m; };
  double a = accel(y, v), overlap = 0;
  for (long step = 0; step < 10'000'000; ++step) {
    const double v_half = v + 0.5 * dt * a;
    y += dt * v_half;
    const double a_new = accel(y, v_half + 0.5 * dt * a);
    v = v_half + 0.5 * dt * a_new;
    a = a_new;
    overlap = std::max(overlap, L - y);
    if (y > L && v > 0) break;
  }
  if (max_overlap) *max_overlap = overlap;
  return v;
}
}  // namespace

TEST_CASE("paper parameter rules and Table 4", "[contact][laws]") {
  const auto p = ContactParams::paper(43.6, paper_mu(0.348));
  CHECK_THAT(p.alpha, WithinRel(43.6 * g0, 1e-15));
  CHECK(p.q == 1.0);
  CHECK_THAT(p.Dc, WithinRel(1.2 * 43.6 * g0, 1e-15));
  CHECK_THAT(p.mu, WithinRel(0.2784, 1e-12));
  // Table 4, as printed (alpha, Dc in kgf; floor mu from Table 2 static values x 0.8, rounded).
  const struct { double alpha, Dc, mu_static, mu_table; } rows[] = {
      {43.6, 52.3, 0.348, 0.278}, {21.3, 25.6, 0.211, 0.169}, {30.5, 36.6, 0.471, 0.377},
      {30.5, 36.6, 0.443, 0.354}, {6.2, 7.4, 0.081, 0.065},   {6.2, 7.4, 0.048, 0.038}};
  for (const auto& r : rows) {
    const auto q = ContactParams::paper(r.alpha, paper_mu(r.mu_static));
    CHECK_THAT(q.Dc / ContactParams::newtons_per_kgf, WithinAbs(r.Dc, 0.05));
    CHECK_THAT(q.mu, WithinAbs(r.mu_table, 0.0005 + 1e-12));
  }
  const auto f = ContactParams::paper_floor(28.8, 0.230, 0.270);
  CHECK(f.mu == 0.230);
  CHECK(f.mu_long == 0.230);
  CHECK(f.mu_short == 0.270);
}

TEST_CASE("negative or NaN parameters throw naming the field", "[contact][laws]") {
  auto message_of = [](const ContactParams& p) {
    try {
      p.validate();
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string("no throw");
  };
  ContactParams p = ContactParams::paper(10, 0.2);
  CHECK_NOTHROW(p.validate());
  p.alpha = -1;
  CHECK_THAT(message_of(p), Catch::Contains("alpha") && Catch::Contains("-1"));
  p = ContactParams::paper(10, 0.2);
  p.mu = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(message_of(p), Catch::Contains("mu ") && Catch::Contains("nan"));
  p = ContactParams::paper(10, 0.2);
  p.Dc = -3.5;
  CHECK_THAT(message_of(p), Catch::Contains("Dc") && Catch::Contains("-3.5"));
  p = ContactParams::paper(10, 0.2);
  p.v_reg = std::numeric_limits<double>::infinity();
  CHECK_THAT(message_of(p), Catch::Contains("v_reg"));
  p = ContactParams::paper(10, 0.2);
  p.q = 0;
  CHECK_THAT(message_of(p), Catch::Contains("q must be positive"));
  p = ContactParams::paper(10, 0.2);
  p.k_lin = -2;
  CHECK_THAT(message_of(p), Catch::Contains("k_lin"));
  CHECK_THROWS_WITH(ContactParams::paper(-5, 0.2), Catch::Contains("alpha"));
  // Law-level checks: StickSlip needs a tangential spring.
  p = ContactParams::paper(10, 0.2);
  CHECK_NOTHROW(PaperLaw::validate(p));
  CHECK_THROWS_WITH(StickSlipLaw::validate(p), Catch::Contains("k_t"));
}

TEST_CASE("the paper's law: equations 1-4 on a hand-computed case", "[contact][laws][paper]") {
  // Tall cabinet: alpha = 43.6 kgf = 427.56994 N, Dc = 1.2 alpha, mu = 0.278; member widths 50 mm,
  // centre lines 45 mm apart -> g = 1 - 45/50 = 0.1.
  ContactParams p = ContactParams::paper(43.6, 0.278);
  const double alpha = 43.6 * g0, Dc = 1.2 * alpha, g = 0.1;
  PaperLaw law;
  CHECK_FALSE(law.clamp_tensile);  // the paper's preset lets F_N pull in the release phase
  // So does every law with the paper's normal response: clamped, its sign damping chatters at rest.
  CHECK_FALSE(StickSlipLaw{}.clamp_tensile);
  CHECK_FALSE(PaperAnisotropicFloorLaw{}.clamp_tensile);
  ContactState st;

  SECTION("indent phase") {
    // v_N = -0.2 (approaching), v_T = 0.3 along x.
    const auto f = law.force(plane_kinematics(0.045, 0.05, Vec3(0.3, 0, -0.2)), p, st);
    const double Fp = alpha * g, FN = Dc * g, FT = 0.278 * alpha * g;  // eqs. 1, 4, 3
    CHECK_THAT(Fp, WithinRel(42.756994, 1e-7));
    CHECK_THAT(FN, WithinRel(51.3083928, 1e-7));
    CHECK_THAT(FT, WithinRel(11.88644433, 1e-7));
    CHECK(f.in_contact);
    CHECK_THAT(f.on_a.z(), WithinRel(Fp + FN, 1e-14));
    CHECK_THAT(f.on_a.x(), WithinRel(-FT, 1e-14));
    CHECK(f.on_a.y() == 0.0);
    CHECK_THAT(f.normal, WithinRel(94.0653868, 1e-7));
    CHECK_THAT(f.tangential, WithinRel(FT, 1e-14));
    CHECK_FALSE(f.sticking);
  }
  SECTION("release phase: F_N reverses; the total pulls unless clamped; friction still scales with alpha g") {
    auto f = law.force(plane_kinematics(0.045, 0.05, Vec3(0, -0.3, 0.2)), p, st);
    CHECK_THAT(f.normal, WithinRel(alpha * g - Dc * g, 1e-13));  // -0.2 alpha g: pulls
    CHECK(f.normal < 0);
    CHECK_THAT(f.on_a.y(), WithinRel(0.278 * alpha * g, 1e-14));
    PaperLaw clamped(true);
    f = clamped.force(plane_kinematics(0.045, 0.05, Vec3(0, -0.3, 0.2)), p, st);
    CHECK(f.normal == 0.0);
    CHECK_THAT(f.on_a.y(), WithinRel(0.278 * alpha * g, 1e-14));
  }
  SECTION("penalty index q = 1.5") {
    p.q = 1.5;
    const auto f = law.force(plane_kinematics(0.045, 0.05, Vec3::Zero()), p, st);
    CHECK_THAT(f.normal, WithinRel(alpha * std::pow(0.1, 1.5), 1e-14));
    CHECK(f.tangential == 0.0);
  }
  SECTION("regularisation near zero speed: ramp below v_reg, tanh as an option") {
    p.v_reg = 1e-3;
    auto f = law.force(plane_kinematics(0.045, 0.05, Vec3(0.5e-3, 0, -0.25e-3)), p, st);
    CHECK_THAT(f.on_a.x(), WithinRel(-0.278 * alpha * g * 0.5, 1e-12));     // v/max(|v|, v_reg)
    CHECK_THAT(f.normal, WithinRel(alpha * g + Dc * g * 0.25, 1e-12));
    CHECK(f.sticking);
    PaperLaw smooth;
    smooth.friction_part().regularisation = SignRegularisation::tanh;
    smooth.damping_part().regularisation = SignRegularisation::tanh;
    f = smooth.force(plane_kinematics(0.045, 0.05, Vec3(0.5e-3, 0, -0.25e-3)), p, st);
    CHECK_THAT(f.on_a.x(), WithinRel(-0.278 * alpha * g * std::tanh(0.5), 1e-12));
    CHECK_THAT(f.normal, WithinRel(alpha * g + Dc * g * std::tanh(0.25), 1e-12));
    p.v_reg = 0;  // exact sign, sign(0) = 0
    f = law.force(plane_kinematics(0.045, 0.05, Vec3(1e-9, 0, 0)), p, st);
    CHECK_THAT(f.on_a.x(), WithinRel(-0.278 * alpha * g, 1e-12));
    CHECK_THAT(f.normal, WithinRel(alpha * g, 1e-14));
  }
  SECTION("no force beyond the contact distance; the state is reset") {
    st.elongation = Vec3(1, 2, 3);
    const auto f = law.force(plane_kinematics(0.0501, 0.05, Vec3(0, 0, -1)), p, st);
    CHECK_FALSE(f.in_contact);
    CHECK(f.on_a == Vec3::Zero());
    CHECK(st.elongation == Vec3::Zero());
    CHECK(law.force(plane_kinematics(0.05, 0.05, Vec3(0, 0, -1)), p, st).in_contact);  // l = L touches, g = 0
  }
}

TEST_CASE("segment pair: equal and opposite forces, no net torque", "[contact][laws][pair]") {
  // Two crossing beams (not at right angles), 50 mm and 30 mm members, sliding and approaching.
  SegmentPair sp;
  sp.a0 = Vec3(-0.3, 0.1, 0.038);
  sp.a1 = Vec3(0.4, -0.05, 0.036);
  sp.b0 = Vec3(0.05, -0.35, -0.002);
  sp.b1 = Vec3(-0.02, 0.4, 0.003);
  sp.va0 = Vec3(0.2, 0.05, -0.1);
  sp.va1 = Vec3(0.3, -0.02, -0.05);
  sp.vb0 = Vec3(-0.1, 0.0, 0.02);
  sp.vb1 = Vec3(0.05, 0.1, 0.0);
  sp.L = 0.5 * (0.05 + 0.03);
  sp.dt = 1e-3;
  const ContactParams p = ContactParams::paper(30.5, 0.169);
  PaperLaw law;
  ContactState st;
  const auto r = evaluate_segment_pair(law, sp, p, st);
  REQUIRE(r.in_contact);
  const auto& c = r.closest;
  REQUIRE(c.s > 0);
  REQUIRE(c.s < 1);
  REQUIRE(c.t > 0);
  REQUIRE(c.t < 1);
  // Kinematics: normal from B to A, velocity interpolated at the closest points.
  CHECK(r.kinematics.n.isApprox((c.p_WA - c.p_WB).normalized(), 1e-14));
  const Vec3 v = (1 - c.s) * sp.va0 + c.s * sp.va1 - ((1 - c.t) * sp.vb0 + c.t * sp.vb1);
  CHECK(r.kinematics.v.isApprox(v, 1e-14));
  CHECK(r.force.tangential > 0);
  // Sharing by the closest-point parameters.
  CHECK(r.on_a0.isApprox((1 - c.s) * r.force.on_a, 1e-14));
  CHECK(r.on_b1.isApprox(-c.t * r.force.on_a, 1e-14));
  const Vec3 net = r.on_a0 + r.on_a1 + r.on_b0 + r.on_b1;
  CHECK(net.norm() < 1e-13 * r.force.on_a.norm());
  CHECK((r.on_a0 + r.on_a1).isApprox(-(r.on_b0 + r.on_b1), 1e-14));
  // Net torque about arbitrary points, with the transfer moments: zero.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 5; ++i) {
    const Vec3 o(u(rng), u(rng), u(rng));
    const Vec3 torque = (sp.a0 - o).cross(r.on_a0) + (sp.a1 - o).cross(r.on_a1) + (sp.b0 - o).cross(r.on_b0) +
                        (sp.b1 - o).cross(r.on_b1) + r.moment_a0 + r.moment_a1 + r.moment_b0 + r.moment_b1;
    CHECK(torque.norm() < 1e-13 * r.force.on_a.norm());
  }
  // Forces alone: the torque is the documented l n x F, which only the tangential part produces.
  const Vec3 forces_only = sp.a0.cross(r.on_a0) + sp.a1.cross(r.on_a1) + sp.b0.cross(r.on_b0) + sp.b1.cross(r.on_b1);
  CHECK(forces_only.isApprox((c.p_WA - c.p_WB).cross(r.force.on_a), 1e-10));
  SECTION("normal force only: zero torque without the moments") {
    SegmentPair still = sp;
    still.va0 = still.va1 = still.vb0 = still.vb1 = Vec3::Zero();
    ContactState s2;
    const auto q = evaluate_segment_pair(law, still, p, s2);
    REQUIRE(q.in_contact);
    CHECK(q.force.tangential == 0.0);
    const Vec3 t = still.a0.cross(q.on_a0) + still.a1.cross(q.on_a1) + still.b0.cross(q.on_b0) + still.b1.cross(q.on_b1);
    CHECK(t.norm() < 1e-14);
    CHECK(q.moment_a0.norm() < 1e-15);
  }
  SECTION("out of reach: nothing") {
    SegmentPair far = sp;
    far.a0.z() += 0.1;
    far.a1.z() += 0.1;
    const auto q = evaluate_segment_pair(law, far, p, st);
    CHECK_FALSE(q.in_contact);
    CHECK(q.on_a0 == Vec3::Zero());
  }
}

TEST_CASE("node against floor and wall helpers", "[contact][laws][pair]") {
  const ContactParams p = ContactParams::paper(20, 0.3);
  PaperLaw law;
  ContactState st;
  NodeOnPlane node;
  node.p_WN = Vec3(0.2, 0.3, 0.02);
  node.v_WN = Vec3(0.1, 0, 0);
  node.L = 0.025;
  node.dt = 1e-3;
  const auto r = evaluate_node_plane(law, node, Plane{}, p, st);
  REQUIRE(r.in_contact);
  const double g = 1 - 0.02 / 0.025;
  CHECK_THAT(r.on_node.z(), WithinRel(p.alpha * g, 1e-14));
  CHECK_THAT(r.on_node.x(), WithinRel(-0.3 * p.alpha * g, 1e-14));
  // The friction acts at the middle of the overlap, 0.5 (l + L) below the node.
  CHECK(r.moment_on_node.isApprox(Vec3(0, 0, -0.5 * (0.02 + 0.025)).cross(r.on_node), 1e-14));
  // Behind the plane the penalty keeps growing (g > 1).
  node.p_WN.z() = -0.01;
  node.v_WN.setZero();
  CHECK_THAT(evaluate_node_plane(law, node, Plane{}, p, st).on_node.z(), WithinRel(p.alpha * 1.4, 1e-14));
  // Bounded wall: contact only within its extent; the wall may move (table frame: it does not).
  const Rectangle wall{Vec3(1, 0, 0.5), Vec3(0, 0.5, 0), Vec3(0, 0, 0.5)};
  node.p_WN = Vec3(1.01, 0.2, 0.4);
  auto w = evaluate_node_rectangle(law, node, wall, p, st);
  REQUIRE(w.in_contact);
  CHECK_THAT(w.on_node.x(), WithinRel(p.alpha * (1 - 0.01 / 0.025), 1e-14));
  node.p_WN = Vec3(1.01, 0.6, 0.4);
  w = evaluate_node_rectangle(law, node, wall, p, st);
  CHECK_FALSE(w.in_contact);
  CHECK(w.on_node == Vec3::Zero());
}

TEST_CASE("spring-dashpot impact: restitution exp(-pi zeta / sqrt(1 - zeta^2))", "[contact][laws][impact]") {
  const double m = 2.0, k = 2e4, v0 = 0.5;
  const double omega = std::sqrt(k / m), period = 2 * std::numbers::pi / omega, dt = period / 2000;
  for (double zeta : {0.05, 0.2, 0.5}) {
    ContactParams p;
    p.k_lin = k;
    p.c_lin = 2 * zeta * std::sqrt(k * m);
    p.mu = 0.3;
    p.validate();
    const double e_exact = std::exp(-std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta));
    SpringDashpotLaw linear(false);  // the closed form assumes the dashpot may pull at the end
    const double e = rebound_speed(linear, p, m, v0, dt) / v0;
    INFO("zeta " << zeta << ": e = " << e << ", closed form " << e_exact);
    CHECK_THAT(e, WithinRel(e_exact, 0.01));
    // Default (clamped) law: the mass leaves when the force reaches zero, before the dashpot
    // could pull it back, so it rebounds faster (by about 2 zeta^2 for small zeta).
    SpringDashpotLaw clamped;
    CHECK(clamped.clamp_tensile);
    CHECK(rebound_speed(clamped, p, m, v0, dt) / v0 > e_exact * (1 + zeta * zeta));
  }
}

TEST_CASE("stick-slip: no creep below mu N, sliding above", "[contact][laws][friction]") {
  // A 10 kg block held by the paper's normal response at a fixed penetration so that the normal
  // force is its weight, pushed along x. The block's x motion is integrated explicitly.
  const double m = 10, N = m * g0, mu = 0.3, k_t = 1e5, dt = 1e-4, L = 0.05;
  ContactParams p;
  p.alpha = 50 * N;
  p.Dc = 1.2 * p.alpha;
  p.mu = mu;
  p.k_t = k_t;
  StickSlipLaw::validate(p);
  const double l = L * (1 - N / p.alpha);  // alpha g = N
  struct Run {
    double x = 0, v = 0, max_x = 0, x_half = 0, v_half = 0;
  };
  auto run = [&](const auto& law, const ContactParams& prm, double force, double ramp_time, double total_time) {
    ContactState st;
    Run r;
    const long steps = std::lround(total_time / dt);
    for (long i = 0; i < steps; ++i) {
      if (i == steps / 2) {
        r.x_half = r.x;
        r.v_half = r.v;
      }
      const double t = i * dt;
      const double f_app = force * (ramp_time > 0 ? std::min(1.0, t / ramp_time) : 1.0);
      const auto cf = law.force(plane_kinematics(l, L, Vec3(r.v, 0, 0), dt), prm, st);
      r.v += dt * (f_app + cf.on_a.x()) / m;
      r.x += dt * r.v;
      r.max_x = std::max(r.max_x, std::abs(r.x));
    }
    return r;
  };
  const double F = 0.9 * mu * N;
  SECTION("0.9 mu N applied slowly: displacement F / k_t, no creep") {
    const Run r = run(StickSlipLaw{}, p, F, 1.0, 4.0);
    CHECK(r.max_x <= F / k_t * 1.05);
    CHECK_THAT(r.x, WithinAbs(F / k_t, 0.05 * F / k_t));
    CHECK(std::abs(r.x - r.x_half) <= 0.1 * F / k_t);
  }
  SECTION("0.9 mu N applied at once, critically damped stick spring: no overshoot, no creep") {
    // The friction force of a critically damped step response peaks at 1.135 F (at t = 2/omega),
    // just above mu N here, so the block may slip a little once; it then holds still.
    ContactParams damped = p;
    damped.c_t = 2 * std::sqrt(k_t * m);
    const Run r = run(StickSlipLaw{}, damped, F, 0.0, 4.0);
    CHECK(r.max_x <= F / k_t * 1.02);
    CHECK(std::abs(r.x - r.x_half) <= 1e-3 * F / k_t);
    CHECK(std::abs(r.v) < 1e-9);
    // At 0.8 mu N the peak stays inside the cone: the displacement is exactly F / k_t.
    const Run r8 = run(StickSlipLaw{}, damped, 0.8 * mu * N, 0.0, 4.0);
    CHECK_THAT(r8.x, WithinRel(0.8 * mu * N / k_t, 1e-6));
  }
  SECTION("0.9 mu N applied at once, undamped: the overshoot may slip once, then it holds") {
    const Run r = run(StickSlipLaw{}, p, F, 0.0, 4.0);
    CHECK(std::abs(r.x - r.x_half) <= 2 * F / k_t);  // oscillates in place between 2 s and 4 s
    CHECK(r.max_x < 10 * F / k_t);
  }
  SECTION("1.1 mu N: slides with (F - mu N)/m acceleration") {
    const double F_slide = 1.1 * mu * N, T = 2.0, a = (F_slide - mu * N) / m;
    const Run r = run(StickSlipLaw{}, p, F_slide, 0.0, T);
    CHECK(r.x > 0.5);
    CHECK_THAT(r.v - r.v_half, WithinRel(a * T / 2, 1e-3));
    CHECK_THAT(r.x - r.x_half, WithinRel(r.v_half * T / 2 + 0.5 * a * (T / 2) * (T / 2), 1e-3));
  }
  SECTION("the regularised Coulomb law creeps under the same 0.9 mu N") {
    ContactLaw<PowerPenalty, PaperSignDamping, RegularisedCoulomb> creeping;
    creeping.friction_part().normal = FrictionNormal::penalty;
    const Run r = run(creeping, p, F, 0.0, 4.0);
    // Steady creep speed where mu N v / sqrt(v^2 + v_reg^2) = F: v = 0.9/sqrt(0.19) v_reg.
    const double v_creep = 0.9 / std::sqrt(1 - 0.81) * p.v_reg;
    CHECK(r.x > 10 * F / k_t);
    CHECK_THAT(r.x - r.x_half, WithinRel(v_creep * 2.0, 0.02));
  }
}

TEST_CASE("stick-slip spring follows a rotating contact plane", "[contact][laws][friction]") {
  ContactParams p = ContactParams::paper(10, 0.5);
  p.k_t = 1e4;
  StickSlipLaw law;
  ContactState st;
  auto k = plane_kinematics(0.04, 0.05, Vec3(0.01, 0, 0), 1e-3);
  law.force(k, p, st);  // elongation 1e-5 along x, sticking
  REQUIRE(st.sticking);
  REQUIRE(st.elongation.isApprox(Vec3(1e-5, 0, 0)));
  k.n = Vec3(1, 0, 1).normalized();  // the contact plane tilts by 45 degrees
  k.v.setZero();
  const auto f = law.force(k, p, st);
  CHECK_THAT(st.elongation.dot(k.n), WithinAbs(0.0, 1e-20));
  CHECK_THAT(st.elongation.norm(), WithinRel(1e-5, 1e-12));  // length kept
  CHECK_THAT(f.tangential, WithinRel(p.k_t * 1e-5, 1e-12));
}

TEST_CASE("anisotropic floor friction: mu_long, mu_short and the ellipse between", "[contact][laws][friction]") {
  ContactParams p = ContactParams::paper_floor(28.8, 0.30, 0.20);
  PaperAnisotropicFloorLaw law;
  ContactState st;
  const double alpha_g = p.alpha * 0.2;  // l = 0.04, L = 0.05
  auto friction = [&](const Vec3& v_t, const Vec3& axis) {
    auto k = plane_kinematics(0.04, 0.05, v_t);
    k.long_axis = axis;
    const auto f = law.force(k, p, st);
    const Vec3 f_t = f.on_a - f.normal * k.n;
    CHECK(f_t.dot(v_t) < 0);
    CHECK(f_t.cross(v_t).norm() < 1e-12 * f_t.norm() * v_t.norm());  // opposite to v_T
    return f.tangential / alpha_g;
  };
  const Vec3 x = Vec3::UnitX();
  CHECK_THAT(friction(Vec3(0.2, 0, 0), x), WithinRel(0.30, 1e-14));
  CHECK_THAT(friction(Vec3(-0.2, 0, 0), x), WithinRel(0.30, 1e-14));
  CHECK_THAT(friction(Vec3(0, 0.2, 0), x), WithinRel(0.20, 1e-14));
  const double mu45 = 1 / std::sqrt(0.5 / (0.3 * 0.3) + 0.5 / (0.2 * 0.2));
  CHECK_THAT(friction(Vec3(0.1, 0.1, 0), x), WithinRel(mu45, 1e-14));
  CHECK_THAT(friction(Vec3(0.1, -0.1, 0), x), WithinRel(mu45, 1e-14));
  const double phi = 0.3;
  CHECK_THAT(friction(0.2 * Vec3(std::cos(phi), std::sin(phi), 0), x),
             WithinRel(1 / std::sqrt(std::pow(std::cos(phi) / 0.3, 2) + std::pow(std::sin(phi) / 0.2, 2)), 1e-13));
  // The item turned by 90 degrees swaps the values; an axis with a normal component is projected;
  // without an axis, mu_long.
  CHECK_THAT(friction(Vec3(0.2, 0, 0), Vec3::UnitY()), WithinRel(0.20, 1e-14));
  CHECK_THAT(friction(Vec3(0.2, 0, 0), Vec3(1, 0, 1).normalized()), WithinRel(0.30, 1e-14));
  CHECK_THAT(friction(Vec3(0, 0.2, 0), Vec3::Zero()), WithinRel(0.30, 1e-14));
  // Equal coefficients reduce it to the paper's isotropic friction.
  p.mu_short = p.mu_long = p.mu = 0.25;
  PaperLaw iso;
  const auto k = plane_kinematics(0.04, 0.05, Vec3(0.13, -0.07, -0.02));
  CHECK(law.force(k, p, st).on_a.isApprox(iso.force(k, p, st).on_a, 1e-14));
}

TEST_CASE("Hunt-Crossley law", "[contact][laws]") {
  ContactParams p;
  p.k_hc = 1e6;
  p.hc_damping = 0.5;
  p.mu = 0.2;
  HuntCrossleyLaw law;
  ContactState st;
  // overlap d = 5 mm approaching at 0.2 m/s: k d^1.5 (1 + 1.5 * 0.5 * 0.2)
  auto f = law.force(plane_kinematics(0.045, 0.05, Vec3(0, 0, -0.2)), p, st);
  CHECK_THAT(f.normal, WithinRel(1e6 * std::pow(0.005, 1.5) * 1.15, 1e-13));
  // fast release: the bracket turns negative and the clamp removes the pull
  f = law.force(plane_kinematics(0.045, 0.05, Vec3(0, 0, 3.0)), p, st);
  CHECK(f.normal == 0.0);
}

TEST_CASE("two laws on the same kinematics: PaperLaw against SpringDashpotLaw", "[contact][laws][compare]") {
  // With k_lin = alpha / L the two laws have the same static stiffness, hence the same static
  // penetration under a weight; their transient forces differ (constant-magnitude vs viscous
  // damping), so the same drop gives different peaks and rebounds.
  const double m = 10, W = m * g0, L = 0.05;
  ContactParams paper = ContactParams::paper(10 * m, 0.3);  // alpha = 10 x weight: g = 0.1 at rest
  ContactParams spring;
  spring.k_lin = paper.alpha / L;
  spring.c_lin = 2 * 0.3 * std::sqrt(spring.k_lin * m);
  spring.mu = 0.3;
  PaperLaw paper_law;
  SpringDashpotLaw spring_law;
  ContactState s1, s2;

  const double l_static = L * (1 - W / paper.alpha);
  const auto k_static = plane_kinematics(l_static, L, Vec3::Zero());
  CHECK_THAT(paper_law.force(k_static, paper, s1).normal, WithinRel(W, 1e-13));
  CHECK_THAT(spring_law.force(k_static, spring, s2).normal, WithinRel(W, 1e-13));
  const auto k_moving = plane_kinematics(l_static, L, Vec3(0.1, 0, -0.1));
  const auto fp = paper_law.force(k_moving, paper, s1), fs = spring_law.force(k_moving, spring, s2);
  CHECK_THAT(fp.normal, WithinRel(W + 1.2 * W, 1e-13));                     // Dc g = 1.2 alpha g
  CHECK_THAT(fs.normal, WithinRel(W + spring.c_lin * 0.1, 1e-13));
  CHECK_THAT(fp.tangential, WithinRel(0.3 * W, 1e-13));                     // mu alpha g
  CHECK_THAT(fs.tangential, WithinRel(0.3 * fs.normal * 0.1 / std::hypot(0.1, spring.v_reg), 1e-13));

  // Drop both at 0.5 m/s under gravity and let them settle. Below v_reg the paper's
  // constant-magnitude damping acts as a dashpot Dc g / v_reg, so an item pressed deeper than its
  // static penetration creeps back with the time constant 1.2 g L / v_reg (q = 1): 6 s at
  // v_reg = 1 mm/s and g = 0.1. With the exact sign it would stay wherever |alpha g - W| < Dc g.
  paper.v_reg = 0.01;  // time constant 0.6 s
  auto drop = [&](const auto& law, const ContactParams& p, double* peak) {
    ContactState st;
    double y = L, v = -0.5, dt = 1e-5;
    *peak = 0;
    for (int i = 0; i < 800000; ++i) {
      const double f = law.force(plane_kinematics(y, L, Vec3(0, 0, v), dt), p, st).on_a.z();
      v += dt * (f / m - g0);
      y += dt * v;
      *peak = std::max(*peak, L - y);
    }
    return y;
  };
  double peak_paper = 0, peak_spring = 0;
  const double y_paper = drop(paper_law, paper, &peak_paper), y_spring = drop(spring_law, spring, &peak_spring);
  CHECK_THAT(y_paper, WithinAbs(l_static, 1e-3 * L));
  CHECK_THAT(y_spring, WithinAbs(l_static, 1e-3 * L));
  INFO("peak penetration: paper " << peak_paper << " m, spring-dashpot " << peak_spring << " m");
  CHECK(std::abs(peak_paper - peak_spring) > 0.05 * peak_spring);
}

// The minimal law of docs/contact/contact.md: a ContactLawPolicy without ContactLaw.
namespace {
struct ConstantPush {
  double magnitude = 1.0;
  ContactForce force(const ContactKinematics& k, const ContactParams&, ContactState&) const {
    ContactForce f;
    if (k.l > k.L) return f;
    f.in_contact = true;
    f.normal = magnitude;
    f.on_a = magnitude * k.n;
    return f;
  }
};
struct NotALaw {
  double force(const ContactKinematics&) const { return 0; }
};
// A user part: a cubic penalty written as a Normal policy.
struct CubicPenalty {
  double force(const ContactKinematics&, const ContactParams& p, double g, double) const { return p.alpha * g * g * g; }
};
}  // namespace

TEST_CASE("laws are checked by the ContactLawPolicy concept; user laws and parts plug in", "[contact][laws]") {
  STATIC_REQUIRE(ContactLawPolicy<PaperLaw>);
  STATIC_REQUIRE(ContactLawPolicy<SpringDashpotLaw>);
  STATIC_REQUIRE(ContactLawPolicy<StickSlipLaw>);
  STATIC_REQUIRE(ContactLawPolicy<ConstantPush>);
  STATIC_REQUIRE_FALSE(ContactLawPolicy<NotALaw>);
  STATIC_REQUIRE_FALSE(ContactLawPolicy<int>);
  STATIC_REQUIRE(PaperLaw::paper_equations);
  STATIC_REQUIRE_FALSE(SpringDashpotLaw::paper_equations);

  SegmentPair sp;
  sp.a0 = Vec3(-1, 0, 0.03);
  sp.a1 = Vec3(1, 0, 0.03);
  sp.b0 = Vec3(0, -1, 0);
  sp.b1 = Vec3(0, 1, 0);
  sp.L = 0.05;
  ContactState st;
  const auto r = evaluate_segment_pair(ConstantPush{2.0}, sp, ContactParams{}, st);
  CHECK(r.on_a0.isApprox(Vec3(0, 0, 1)));
  CHECK(r.on_b1.isApprox(Vec3(0, 0, -1)));

  ContactLaw<CubicPenalty, NoDamping, PaperSignFriction> cubic;
  ContactParams p;
  p.alpha = 100;
  CHECK_THAT(cubic.force(plane_kinematics(0.04, 0.05, Vec3::Zero()), p, st).normal, WithinRel(100 * 0.008, 1e-14));
}

}  // namespace laws_tests
