// The geometry occupants and exits see (harm/item_box.hpp), against hand-computed boxes.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include <furniture_fem/harm/exit_path.hpp>  // polygon_area
#include <furniture_fem/harm/item_box.hpp>

#include "test_boxes.hpp"

using namespace furniture_fem;
using test::cabinet;


TEST_CASE("A placed box stands on its footprint, its outline is its footprint", "[harm][box]") {
  const ItemInfo it = cabinet(0.9, 0.4, 1.8, Vec3(1.0, 2.0, 0.0));
  const OrientedBox b = placed_box(it);
  CHECK(b.centre.isApprox(Vec3(1.0, 2.0, 0.9)));
  const auto outline = plan_outline(b);
  REQUIRE(outline.size() == 4);
  CHECK(polygon_area(outline) == Approx(0.9 * 0.4).epsilon(1e-12));  // counter-clockwise: positive
  CHECK(b.distance(Vec3(1.0, 2.0 - 0.2 - 0.3, 1.0)) == Approx(0.3).epsilon(1e-12));  // 0.3 m in front
  CHECK(b.distance(Vec3(1.2, 2.1, 0.5)) == 0.0);                                     // inside
  CHECK(b.signed_distance(Vec3(1.2, 2.1, 0.5)) == Approx(-0.1).epsilon(1e-12));      // 0.1 m below the back face
  CHECK(b.signed_distance(Vec3(1.0, 2.0 - 0.2 - 0.3, 1.0)) == Approx(0.3).epsilon(1e-12));
}

TEST_CASE("A box tipped forward by 90 degrees about its front bottom edge lies on its front face",
          "[harm][box]") {
  // The cabinet (W 0.9, D 0.4, H 1.8) at the origin; its front is at y = -0.2. Tipped about the front
  // bottom edge (y = -0.2, z = 0), it lies with its top at y = -0.2 - 1.8 and its back face up at z = 0.4.
  const double W = 0.9, D = 0.4, H = 1.8;
  const ItemInfo it = cabinet(W, D, H, Vec3::Zero());
  const Mat3 Q = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()).matrix();  // top goes to -y
  const Vec3 pivot(0.0, -0.5 * D, 0.0);
  // The nodes' centroid is any point moved rigidly: take the box's centre.
  const Vec3 Xc(0.0, 0.0, 0.5 * H);
  const Vec3 xc = pivot + Q * (Xc - pivot);
  const OrientedBox b = item_box(it, Q, Xc, xc);
  double lo_y = 1e9, hi_y = -1e9, lo_z = 1e9, hi_z = -1e9;
  for (const Vec3& c : b.corners()) {
    lo_y = std::min(lo_y, c.y()), hi_y = std::max(hi_y, c.y());
    lo_z = std::min(lo_z, c.z()), hi_z = std::max(hi_z, c.z());
  }
  CHECK(lo_y == Approx(-0.5 * D - H).epsilon(1e-12));
  CHECK(hi_y == Approx(-0.5 * D).epsilon(1e-12));
  CHECK(lo_z == Approx(0.0).margin(1e-12));
  CHECK(hi_z == Approx(D).epsilon(1e-12));
  CHECK(polygon_area(plan_outline(b)) == Approx(W * H).epsilon(1e-12));
}

TEST_CASE("The plan outline of a box turned about the vertical is the turned rectangle", "[harm][box]") {
  // A 1 x 1 square turned by 45 degrees: a diamond of the same area reaching sqrt(2)/2 along x.
  ItemInfo it = cabinet(1.0, 1.0, 0.5, Vec3::Zero());
  it.R = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitZ()).matrix();
  const auto outline = plan_outline(placed_box(it));
  REQUIRE(outline.size() == 4);
  CHECK(polygon_area(outline) == Approx(1.0).epsilon(1e-12));
  double reach = 0.0;
  for (const Vec2& p : outline) reach = std::max(reach, p.x());
  CHECK(reach == Approx(std::sqrt(0.5)).epsilon(1e-12));
  // A tilted box's outline drops the corners hidden inside it: 8 corners, 6 on the hull.
  const Mat3 tilt = Eigen::AngleAxisd(0.3, Vec3(1.0, 1.0, 0.0).normalized()).matrix();
  CHECK(plan_outline(item_box(cabinet(1.0, 1.0, 1.0, Vec3::Zero()), tilt, Vec3::Zero(), Vec3::Zero())).size() == 6);
}
