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
