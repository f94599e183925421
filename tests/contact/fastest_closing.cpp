// RoomContact::fastest_closing (the simulation's impact sub-steps, docs/contact/implicit_contact.md,
// "Impacts: sub-steps"): the fastest speed at which a node closes on a plane that it touches or would
// reach within the step at that speed; nodes moving away, too far to arrive, or beside a wall panel's
// extent do not count. Checked against the speeds and gaps set by hand.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <vector>

using namespace furniture_fem;

namespace fastest_closing_tests {  // this file's own names (its group compiles files in batches)

TEST_CASE("fastest_closing: the fastest node that closes on a floor or wall within the step", "[contact][impact]") {
  // Two nodes of one member (a 50 mm tube: contact distance 25 mm), the floor z = 0 and a wall x = 1
  // facing -X that spans y in [-1, 1] only.
  Model m;
  const int body = m.add_body("bar");
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002, "50 x 50")), mat = m.add_material(Material::steel());
  const int a = m.add_node({0, 0, 0.5}, body), b = m.add_node({0.5, 0, 0.5}, body);
  m.add_member("bar", a, b, sec, mat);
  RigidPlane wall;
  wall.point = Vec3(1, 0, 0);
  wall.normal = -Vec3::UnitX();
  wall.axis_u = Vec3::UnitY();
  wall.axis_v = Vec3::UnitZ();
  wall.half_u = 1.0;
  wall.half_v = 10.0;
  wall.is_wall = true;
  RoomContact contact(m, {BodyContact{}}, {RigidPlane{}, wall});
  const double L = 0.025, dt = 1e-3;

  std::vector<Vec3> x(m.num_nodes());
  std::vector<Mat3> R(m.num_nodes(), Mat3::Identity());
  Eigen::VectorXd v = Eigen::VectorXd::Zero(6 * m.num_nodes());
  const auto fastest = [&] { return contact.fastest_closing(ContactView{m, x, v, 0.0, dt, &R}); };
  const auto place = [&](int n, Vec3 at, Vec3 vel) {
    x[n] = at;
    v.segment<3>(6 * n) = vel;
  };

  // Node a 4 mm above contact (its centre L + 4 mm up): falling at 5 m/s it arrives within 1 ms, at
  // 3 m/s it does not.
  place(a, Vec3(0, 0, L + 0.004), Vec3(0, 0, -5));
  place(b, Vec3(0.5, 0, 0.5), Vec3(0, 0, -1));
  CHECK(fastest() == Approx(5.0));
  place(a, Vec3(0, 0, L + 0.004), Vec3(0, 0, -3));
  CHECK(fastest() == 0.0);
  // In contact (2 mm in) and still closing slowly: it counts; moving away: it does not.
  place(a, Vec3(0, 0, L - 0.002), Vec3(0.3, 0, -0.2));
  CHECK(fastest() == Approx(0.2));
  place(a, Vec3(0, 0, L - 0.002), Vec3(0, 0, 0.2));
  CHECK(fastest() == 0.0);
  // Node b 1 mm from the wall, thrown at it at 7 m/s, and then beside its panel (y = 1.5).
  place(b, Vec3(1 - L - 0.001, 0, 0.5), Vec3(7, 0, 0));
  CHECK(fastest() == Approx(7.0));
  place(b, Vec3(1 - L - 0.001, 1.5, 0.5), Vec3(7, 0, 0));
  CHECK(fastest() == 0.0);
  // Both closing: the faster wins.
  place(a, Vec3(0, 0, L), Vec3(0, 0, -2));
  place(b, Vec3(1 - L - 0.001, 0, 0.5), Vec3(1.5, 0, 0));
  CHECK(fastest() == Approx(2.0));
}

}  // namespace fastest_closing_tests
