// Setting up a room of many rigid bodies (RoomContact::set_rigid of many bodies at once, its hull pairs
// found by sweeping boxes): the same room as setting the bodies rigid one by one, and the same nested
// pairs as testing every pair of hulls (issue 51, item 4: a room of n items set up in about n log n).
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace furniture_fem;

namespace room_setup_tests {  // this file's own names (its group compiles files in batches)

// A box frame of 50 mm tubes (two elements per edge), size a x b x h, its bottom centre at c, turned by
// yaw about z.
int add_box(Model& m, int sec, int mat, Vec3 c, double a, double b, double h, double yaw) {
  const int body = m.add_body("box " + std::to_string(m.num_bodies()));
  const Mat3 R = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
  int n[8];
  for (int k = 0; k < 8; ++k)
    n[k] = m.add_node(c + R * Vec3((k & 1 ? 0.5 : -0.5) * a, (k & 2 ? 0.5 : -0.5) * b, (k & 4 ? h : 0.0)), body);
  MemberOptions two;
  two.elements = 2;  // ASI-Gauss elements come in pairs
  const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (const auto& e : edges) m.add_member("edge", n[e[0]], n[e[1]], sec, mat, two);
  return body;
}

// 60 boxes: a grid of them, some far apart, some touching, some inside a larger one (nested at rest),
// some turned, sizes drawn from a fixed seed.
Model room(std::vector<int>& bodies) {
  Model m;
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002, "50 x 50"));
  const int mat = m.add_material(Material::steel());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> size(0.2, 0.9), jitter(-0.3, 0.3), yaw(0.0, std::numbers::pi / 2);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 8; ++j) {
      const Vec3 c(1.0 * i + jitter(rng), 1.0 * j + jitter(rng), 0);
      bodies.push_back(add_box(m, sec, mat, c, size(rng), size(rng), size(rng), (i + j) % 3 == 0 ? yaw(rng) : 0.0));
    }
  // Nested at rest: small boxes inside big ones, and one overlapping a neighbour by 0.1 m.
  for (int k = 0; k < 6; ++k) {
    const Vec3 c(10.0 + 2.0 * k, 0, 0);
    bodies.push_back(add_box(m, sec, mat, c, 1.5, 1.5, 1.0, 0.1 * k));
    bodies.push_back(add_box(m, sec, mat, c + Vec3(0.1, -0.1, 0.2), 0.4, 0.3, 0.3, 0.2 * k));
  }
  bodies.push_back(add_box(m, sec, mat, Vec3(22.0, 0, 0), 1.0, 1.0, 1.0, 0));
  bodies.push_back(add_box(m, sec, mat, Vec3(22.9, 0, 0), 1.0, 1.0, 1.0, 0));
  bodies.push_back(add_box(m, sec, mat, Vec3(25.0, 0, 0), 1.0, 1.0, 1.0, 0));
  bodies.push_back(add_box(m, sec, mat, Vec3(26.0, 0, 0), 1.0, 1.0, 1.0, 0));  // touching its neighbour
  return m;
}

TEST_CASE("a room set rigid at once is the room set rigid body by body; its nested pairs are every pair's",
          "[contact][room_setup]") {
  std::vector<int> bodies;
  const Model m = room(bodies);
  const int nb = m.num_bodies();
  for (bool surface : {false, true}) {
    INFO("contact at the " << (surface ? "surfaces" : "centre lines"));
    const auto make = [&] {
      RoomContact c(m, std::vector<BodyContact>(nb), {RigidPlane{}});
      c.set_surface(m, surface);
      c.set_rigid_pair_hulls(m, true);
      return c;
    };
    RoomContact one_by_one = make(), at_once = make();
    for (int b : bodies) one_by_one.set_rigid(m, b);
    at_once.set_rigid(m, bodies);
    CHECK(at_once.plane_nodes() == one_by_one.plane_nodes());
    REQUIRE(at_once.surface_points().size() == one_by_one.surface_points().size());
    for (std::size_t i = 0; i < at_once.surface_points().size(); ++i) {
      CHECK(at_once.surface_points()[i].node == one_by_one.surface_points()[i].node);
      CHECK(at_once.surface_points()[i].arm0 == one_by_one.surface_points()[i].arm0);
    }
    // Every pair's hulls tested at rest (as before the sweep): nested when they overlap by more than
    // 5 mm beyond the contact distance (25 mm per body at the centre lines, none at the surfaces).
    int nested = 0, hull_pairs = 0;
    for (int a = 0; a < nb; ++a)
      for (int b = 0; b < nb; ++b) {
        if (a == b) {
          CHECK_FALSE(at_once.hull_pair(a, b));
          continue;
        }
        const auto hull = [&](int body) { return detail::support_geometry(m, m.body(body).nodes); };
        const auto rest = [&](int i) -> Vec3 { return m.node(i).X; };
        bool expect = true;
        if (!surface) {  // at the surfaces the hulls are of the cubes around the nodes: the room's own
          expect = detail::hull_separation(hull(a), rest, hull(b), rest, 0.05) >= -0.005;
          CHECK(at_once.hull_pair(a, b) == expect);
        }
        CHECK(at_once.hull_pair(a, b) == one_by_one.hull_pair(a, b));
        nested += !at_once.hull_pair(a, b);
        hull_pairs += at_once.hull_pair(a, b);
      }
    // The room has both kinds: 6 boxes in boxes and one pair overlapping by 0.1 m (at least 7 pairs,
    // each counted both ways), and most pairs by their hulls.
    CHECK(nested >= 14);
    CHECK(hull_pairs > nb * (nb - 1) / 2);
  }
}

}  // namespace room_setup_tests
