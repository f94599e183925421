// The reduced contact geometry of a rigid body (contact/detail/support_points.hpp): a box's hull
// vertices and faces, each face's share, and the same geometry to the bit whatever order the nodes
// (hence CGAL's hull) come in. Before the fix, the faces' frames and vertex order followed CGAL's
// listing, which depends on where its data lie in memory: configuration 3 at rigid fidelity gave
// other outcomes from one process to another (docs/performance.md section 8).
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <algorithm>
#include <random>
#include <vector>

using namespace furniture_fem;

namespace support_geometry_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A 0.4 x 0.3 x 0.5 m box: its 8 corners, a node at the middle of every edge and one at each face's
// centre (on the hull's faces but not vertices), and 3 inside.
std::vector<int> box_nodes(Model& m, int body) {
  std::vector<int> nodes;
  const double a = 0.4, b = 0.3, c = 0.5;
  for (double x : {0.0, 0.5 * a, a})
    for (double y : {0.0, 0.5 * b, b})
      for (double z : {0.0, 0.5 * c, c}) nodes.push_back(m.add_node({x, y, z}, body));
  nodes.push_back(m.add_node({0.1, 0.1, 0.1}, body));
  nodes.push_back(m.add_node({0.3, 0.2, 0.4}, body));
  nodes.push_back(m.add_node({0.2, 0.1, 0.3}, body));
  return nodes;
}

bool same(const detail::SupportGeometry& g, const detail::SupportGeometry& h) {
  if (g.vertices != h.vertices || g.faces.size() != h.faces.size()) return false;
  for (std::size_t k = 0; k < g.faces.size(); ++k)
    if (g.faces[k].frame != h.faces[k].frame || g.faces[k].vertices != h.faces[k].vertices ||
        g.faces[k].share != h.faces[k].share)
      return false;
  return true;
}

}  // namespace

TEST_CASE("a box's support geometry: 8 vertices, 6 faces, each face's share", "[contact][support]") {
  Model m;
  const int body = m.add_body("box");
  const auto nodes = box_nodes(m, body);
  const detail::SupportGeometry g = detail::support_geometry(m, nodes);
  CHECK(g.vertices.size() == 8);
  REQUIRE(g.faces.size() == 6);
  for (const auto& f : g.faces) {
    CHECK(f.vertices.size() == 4);
    CHECK(f.share == 9.0 / 4.0);  // 9 nodes on each face (corners, edge middles, centre) for 4 vertices
    CHECK(std::is_sorted(f.vertices.begin(), f.vertices.end()));
  }
}

TEST_CASE("a box's support geometry is the same to the bit whatever the order of its nodes", "[contact][support]") {
  Model m;
  const int body = m.add_body("box");
  auto nodes = box_nodes(m, body);
  const detail::SupportGeometry reference = detail::support_geometry(m, nodes);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    std::shuffle(nodes.begin(), nodes.end(), rng);
    INFO("shuffle " << trial);
    CHECK(same(detail::support_geometry(m, nodes), reference));
  }
}

TEST_CASE("at the members' surfaces, two box frames touch planes at their envelopes' corners", "[contact][support][surface]") {
  // Two rigid frames of 50 x 50 mm tubes (the second turned by 30 deg about z, away from the first):
  // with RoomContact::set_surface each one's support points are the 8 corners of its outer envelope,
  // 25 mm outside its members' centre lines along its own axes, each point owned by a node of its body.
  Model m;
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002, "50 x 50")), mat = m.add_material(Material::steel());
  const double c = 0.025, a = 0.4, b = 0.3, h = 0.6;
  std::vector<std::vector<Vec3>> envelopes;
  for (int k = 0; k < 2; ++k) {
    const int body = m.add_body("frame " + std::to_string(k));
    const double yaw = k == 0 ? 0.0 : std::acos(-1.0) / 6;
    const Mat3 R = Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix();
    const Vec3 origin(2.0 * k, 0, c);
    int corner[8];
    std::vector<Vec3> envelope;
    for (int i = 0; i < 8; ++i) {
      const Vec3 s((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
      const Vec3 local(0.5 * a * s.x(), 0.5 * b * s.y(), 0.5 * h * (s.z() + 1));
      corner[i] = m.add_node(origin + R * local, body);
      envelope.push_back(origin + R * (local + c * s));
    }
    envelopes.push_back(envelope);
    MemberOptions o;
    o.target_length = 0.1;
    for (int i = 0; i < 8; ++i)
      for (int bit : {1, 2, 4})
        if (!(i & bit)) m.add_member("edge", corner[i], corner[i | bit], sec, mat, o);
  }
  RoomContact contact(m, {BodyContact{}, BodyContact{}}, {RigidPlane{}});
  contact.set_surface(m);
  contact.set_rigid(m, 0);
  contact.set_rigid(m, 1);
  const auto& points = contact.surface_points();
  REQUIRE(points.size() == 16);
  for (int k = 0; k < 2; ++k) {
    for (int i = 0; i < 8; ++i) {
      const auto& p = points[8 * k + i];
      CHECK(m.node(p.node).body == k);
      const Vec3 x = m.node(p.node).X + p.arm0;
      double nearest = 1e300;
      for (const Vec3& e : envelopes[k]) nearest = std::min(nearest, (e - x).norm());
      INFO("frame " << k << ", point " << i << " at " << x.transpose());
      CHECK(nearest < 1e-12);
    }
  }
  // Every corner is some point's (8 distinct points per frame).
  for (int k = 0; k < 2; ++k)
    for (const Vec3& e : envelopes[k])
      CHECK(std::any_of(points.begin() + 8 * k, points.begin() + 8 * k + 8,
                        [&](const auto& p) { return (m.node(p.node).X + p.arm0 - e).norm() < 1e-12; }));
}

TEST_CASE("at the members' surfaces, a flexible frame's every node touches planes at its cube's corners",
          "[contact][support][surface]") {
  // A flexible frame (turned 30 deg about z) keeps no hull: each node gets the 8 corners of its own
  // cube, c = 25 mm along the frame's axes (the corners of a corner node are the envelope's there).
  Model m;
  const int sec = m.add_section(Section::hollow_rectangle(0.05, 0.05, 0.002, "50 x 50")), mat = m.add_material(Material::steel());
  const double c = 0.025;
  const int body = m.add_body("frame");
  const Mat3 R = Eigen::AngleAxisd(std::acos(-1.0) / 6, Vec3::UnitZ()).toRotationMatrix();
  const int n0 = m.add_node(Vec3(0, 0, c), body), n1 = m.add_node(Vec3(0, 0, c) + R * Vec3(0.4, 0, 0), body),
            n2 = m.add_node(Vec3(0, 0, c) + R * Vec3(0.4, 0.3, 0), body);
  MemberOptions o;
  o.target_length = 0.1;
  m.add_member("x", n0, n1, sec, mat, o);
  m.add_member("y", n1, n2, sec, mat, o);
  RoomContact contact(m, {BodyContact{}}, {RigidPlane{}});
  contact.set_surface(m);
  const auto& points = contact.surface_points();
  REQUIRE(points.size() == 8 * m.body(body).nodes.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    CHECK(p.node == m.body(body).nodes[i / 8]);
    // Each offset is +-c along the frame's three axes (x and y turned by 30 deg, z up).
    const Vec3 local = R.transpose() * p.arm0;
    INFO("point " << i << " of node " << p.node << ": " << local.transpose());
    for (int k = 0; k < 3; ++k) CHECK(std::abs(std::abs(local[k]) - c) < 1e-12);
  }
  // The corner node n1 (where the members meet): its cube's outer corners are the frame's envelope.
  const Vec3 outer = m.node(n1).X + R * Vec3(c, -c, -c);
  CHECK(std::any_of(points.begin(), points.end(), [&](const auto& p) { return (m.node(p.node).X + p.arm0 - outer).norm() < 1e-12; }));
  // Back to the centre lines: no surface points, every node tested again.
  contact.set_surface(m, false);
  CHECK(contact.surface_points().empty());
  CHECK(contact.plane_nodes().size() == m.body(body).nodes.size());
}

}  // namespace support_geometry_tests
