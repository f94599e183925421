// A ceiling among RoomContact's planes (RigidPlane::is_ceiling, the scene's "ceiling"): a node pressed
// into it gets the law's force with the body's wall parameters, not its floor ones nor its casters'
// friction, reported with its own partner (RoomContact::ceiling_id); fastest_closing sees a node
// rising at it. Checked against the paper's equations 1 and 3 by hand.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <vector>

using namespace furniture_fem;

namespace ceiling_plane_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("a ceiling plane takes the wall's parameters and is reported as the ceiling", "[contact][ceiling]") {
  // A bar of two nodes (a 50 mm tube: contact distance L = 25 mm), both casters; the floor z = 0 and a
  // ceiling z = 1 facing down. Floor: alpha 100 N, mu 0.5 (casters 0.05); wall: alpha 300 N, mu 0.2.
  Model m;
  const int body = m.add_body("bar");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002, "50 x 50")), mat = m.add_material(Material::steel());
  const int a = m.add_node({0, 0, 0.5}, body), b = m.add_node({0.5, 0, 0.5}, body);
  m.add_member("bar", a, b, sec, mat);
  BodyContact bc;
  bc.floor.alpha = 100;
  bc.floor.mu = bc.floor.mu_long = bc.floor.mu_short = 0.5;
  bc.wall.alpha = 300;
  bc.wall.mu = bc.wall.mu_long = bc.wall.mu_short = 0.2;
  bc.caster_nodes = {a, b};
  bc.caster_mu = 0.05;
  RigidPlane ceiling;
  ceiling.point = Vec3(0, 0, 1);
  ceiling.normal = -Vec3::UnitZ();
  ceiling.is_ceiling = true;
  CHECK_FALSE(ceiling.is_floor());
  CHECK(RigidPlane{}.is_floor());
  RoomContact contact(m, {bc}, {RigidPlane{}, ceiling});
  const double L = 0.025, dt = 1e-3;

  // Node a 5 mm into the ceiling, node b 5 mm into the floor (g = 0.2), both sliding along +X at
  // 0.5 m/s (far above v_reg: friction at its full value), neither closing (no normal damping).
  // The member's other nodes (its elements come in pairs) mid-air, touching nothing.
  std::vector<Vec3> x(m.num_nodes(), Vec3(0.25, 0, 0.5));
  x[a] = Vec3(0, 0, 1 - L + 0.005);
  x[b] = Vec3(0.5, 0, L - 0.005);
  std::vector<Mat3> R(m.num_nodes(), Mat3::Identity());
  Eigen::VectorXd v = Eigen::VectorXd::Zero(6 * m.num_nodes());
  v.segment<3>(6 * a) = v.segment<3>(6 * b) = Vec3(0.5, 0, 0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(6 * m.num_nodes());
  contact.add_forces(ContactView{m, x, v, 0.0, dt, &R}, f);
  const double g = 0.2;
  // Ceiling: alpha_wall g down, mu_wall alpha_wall g against the sliding (not the casters' 0.05).
  const Vec3 on_a(-0.2 * 300 * g, 0, -300 * g), on_b(-0.05 * 100 * g, 0, 100 * g);
  CHECK((Vec3(f.segment<3>(6 * a)) - on_a).norm() < 1e-9);
  CHECK((Vec3(f.segment<3>(6 * b)) - on_b).norm() < 1e-9);
  int reported = 0;
  for (const PairForce& pf : contact.pair_forces()) {
    CHECK(pf.body_a == body);
    const Vec3& expected = pf.body_b == RoomContact::ceiling_id ? on_a : on_b;
    INFO("partner " << pf.body_b << ": " << pf.force_on_a.transpose() << " N, expected " << expected.transpose());
    CHECK((pf.body_b == RoomContact::ceiling_id || pf.body_b == RoomContact::floor_id));
    CHECK((pf.force_on_a - expected).norm() < 1e-9);
    reported += pf.body_b == RoomContact::ceiling_id ? 10 : 1;
  }
  CHECK(reported == 11);  // one of each
  CHECK(contact.pair_forces().size() == 2);

  // Node a 4 mm below contact with the ceiling, rising at 5 m/s: it arrives within 1 ms; at 3 m/s not.
  x.assign(m.num_nodes(), Vec3(0.25, 0, 0.5));
  x[a] = Vec3(0, 0, 1 - L - 0.004);
  v.setZero();
  v.segment<3>(6 * a) = Vec3(0, 0, 5);
  CHECK(contact.fastest_closing(ContactView{m, x, v, 0.0, dt, &R}) == Approx(5.0));
  v.segment<3>(6 * a) = Vec3(0, 0, 3);
  CHECK(contact.fastest_closing(ContactView{m, x, v, 0.0, dt, &R}) == 0.0);
}

}  // namespace ceiling_plane_tests
