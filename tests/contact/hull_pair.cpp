// Two rigid bodies' hulls against each other (contact/detail/hull_pair.hpp): the contact points of a
// box resting on another, against the overlap polygons worked out by hand (the same footprint, shifted
// half a width, turned 45 degrees: an octagon), a box on one edge, boxes apart, and nested hulls.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/room_contact.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

using namespace furniture_fem;

namespace hull_pair_tests {  // this file's own names (its group compiles files in batches)

namespace {

// A box's 8 corners, `size` along its axes, its bottom centre at `base`, turned by `yaw` about z and
// then by `tilt` about x.
detail::support::Points box(const Vec3& size, const Vec3& base, double yaw = 0, double tilt = 0) {
  const Mat3 R = (Eigen::AngleAxisd(tilt, Vec3::UnitX()) * Eigen::AngleAxisd(yaw, Vec3::UnitZ())).toRotationMatrix();
  detail::support::Points P;
  for (int c = 0; c < 8; ++c) {
    const Vec3 local(((c & 1) ? 0.5 : -0.5) * size.x(), ((c & 2) ? 0.5 : -0.5) * size.y(), (c & 4) ? size.z() : 0.0);
    P.push_back(base + R * local);
  }
  return P;
}

struct Hull {
  detail::support::Points P;
  detail::SupportGeometry g;
  explicit Hull(detail::support::Points points) : P(std::move(points)) {
    std::vector<int> ids(P.size());
    for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
    g = detail::hull_geometry(P, ids, ids);
  }
  auto at() const {
    return [this](int i) -> const Vec3& { return P[i]; };
  }
};

bool contact(const Hull& a, const Hull& b, detail::HullPairContact& out, double distance = 0) {
  return detail::hull_pair_contact(a.g, a.at(), b.g, b.at(), distance, 0.0, 1e-3, out);
}

// Whether p lies in the box's footprint (axis-aligned, centred at the origin) and in the turned one.
bool in_square(const Vec3& p, double half, double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  const double u = c * p.x() + s * p.y(), v = -s * p.x() + c * p.y();
  return std::abs(u) <= half + 1e-9 && std::abs(v) <= half + 1e-9;
}

}  // namespace

TEST_CASE("hull pair: a box resting on another touches at the corners of their overlap", "[contact][hulls]") {
  const double depth = 2e-4;  // m the upper box sinks into the lower one
  const Hull lower(box({1, 1, 1}, {0, 0, 0}));

  SECTION("the same footprint: the four corners, each at the overlap depth") {
    const Hull upper(box({1, 1, 0.5}, {0, 0, 1 - depth}));
    detail::HullPairContact hc;
    REQUIRE(contact(lower, upper, hc));
    CHECK(hc.reference_on_a);  // a tie, kept by the lower-numbered body's face
    CHECK(hc.normal.isApprox(Vec3::UnitZ(), 1e-12));
    REQUIRE(hc.points.size() == 4);
    for (const auto& p : hc.points) {
      CHECK(p.kind == detail::HullPointKind::corner);  // corners of the upper box, not crossings
      CHECK(p.gap == Approx(-depth).margin(1e-12));
      CHECK(std::abs(p.x.x()) == Approx(0.5));
      CHECK(std::abs(p.x.y()) == Approx(0.5));
    }
    // Either body's face may be the reference when the roles are swapped: the contact points are the same.
    detail::HullPairContact swapped;
    REQUIRE(contact(upper, lower, swapped));
    CHECK(swapped.reference_on_a);
    CHECK(swapped.normal.isApprox(-Vec3::UnitZ(), 1e-12));
    CHECK(swapped.points.size() == 4);
  }
  SECTION("shifted by half a width: two corners and two crossings, spanning the overlap") {
    const Hull upper(box({1, 1, 0.5}, {0.5, 0, 1 - depth}));
    detail::HullPairContact hc;
    REQUIRE(contact(lower, upper, hc));
    REQUIRE(hc.points.size() == 4);
    int corners = 0;
    double xmin = 1, xmax = -1;
    for (const auto& p : hc.points) {
      corners += p.kind == detail::HullPointKind::corner;
      xmin = std::min(xmin, p.x.x()), xmax = std::max(xmax, p.x.x());
      CHECK(p.gap == Approx(-depth).margin(1e-12));
      CHECK(std::abs(p.x.y()) == Approx(0.5));
    }
    CHECK(corners == 2);
    CHECK(xmin == Approx(0.0).margin(1e-12));
    CHECK(xmax == Approx(0.5));
  }
  SECTION("turned by 45 degrees: the eight corners of the octagon both squares share") {
    const double yaw = std::acos(-1.0) / 4;
    const Hull upper(box({1, 1, 0.5}, {0, 0, 1 - depth}, yaw));
    detail::HullPairContact hc;
    REQUIRE(contact(lower, upper, hc));
    REQUIRE(hc.points.size() == 8);
    for (const auto& p : hc.points) {
      // No corner of either square lies in the other: each edge of the upper one enters and leaves.
      CHECK((p.kind == detail::HullPointKind::entering || p.kind == detail::HullPointKind::leaving));
      CHECK(in_square(p.x, 0.5, 0));
      CHECK(in_square(p.x, 0.5, yaw));
      // The octagon's corners lie on the sides of both squares.
      const double r = std::max(std::abs(p.x.x()), std::abs(p.x.y()));
      CHECK(r == Approx(0.5));
    }
  }
  SECTION("a small box on a large one: its own four corners") {
    const Hull upper(box({0.3, 0.2, 0.3}, {0.1, -0.2, 1 - depth}));
    detail::HullPairContact hc;
    REQUIRE(contact(lower, upper, hc));
    CHECK(hc.points.size() == 4);
    for (const auto& p : hc.points) CHECK(p.kind == detail::HullPointKind::corner);
    // With the small box first, its bottom face is the reference (ties go to the first hull): the
    // large face's points under its four corners.
    detail::HullPairContact swapped;
    REQUIRE(contact(upper, lower, swapped));
    REQUIRE(swapped.points.size() == 4);
    for (const auto& p : swapped.points) {
      CHECK(p.kind == detail::HullPointKind::reference);
      CHECK(p.gap == Approx(-depth).margin(1e-12));
      CHECK(p.x.z() == Approx(1.0));  // on the lower box's top face
      CHECK(std::abs(p.x.x() - 0.1) == Approx(0.15));
      CHECK(std::abs(p.x.y() + 0.2) == Approx(0.1));
    }
  }
  SECTION("the same footprint nudged sideways: the points keep their names, so their friction history follows") {
    // Shifted by 10 um, then by 20 um: two corners stay inside; the other two are outside, and the
    // edges from them enter the reference face: the same four names both times.
    const auto names = [&](double shift) {
      const Hull upper(box({1, 1, 0.5}, {shift, 0, 1 - depth}));
      detail::HullPairContact hc;
      REQUIRE(contact(lower, upper, hc));
      std::vector<std::array<int, 3>> n;
      for (const auto& p : hc.points) n.push_back({static_cast<int>(p.kind), p.id, p.id2});
      std::sort(n.begin(), n.end());
      return n;
    };
    const auto a = names(1e-5), b = names(2e-5);
    CHECK(a.size() == 4);
    CHECK(a == b);
  }
}

TEST_CASE("hull pair: a tilted box touches on its lower edge; boxes apart do not touch", "[contact][hulls]") {
  const Hull lower(box({1, 1, 1}, {0, 0, 0}));
  // Tilted by 0.01 rad about x and lowered so that its lowest edge (y = +0.5 side after the turn goes
  // down) sinks 0.1 mm: only that edge's two corners touch.
  const double tilt = 0.01, sink = 1e-4;
  auto P = box({0.6, 0.6, 0.5}, {0, 0, 0}, 0, tilt);
  double zmin = 1e9;
  for (const auto& x : P) zmin = std::min(zmin, x.z());
  for (auto& x : P) x.z() += 1 - zmin - sink;
  const Hull upper(P);
  detail::HullPairContact hc;
  REQUIRE(contact(lower, upper, hc));
  REQUIRE(hc.points.size() == 2);
  for (const auto& p : hc.points) CHECK(p.gap == Approx(-sink).margin(1e-12));

  // Raised 1 mm above the lower box: no contact; with a contact distance of 2 mm (members' half
  // widths at centre lines), touching by 1 mm.
  for (auto& x : P) x.z() += sink + 1e-3;
  const Hull above(P);
  CHECK_FALSE(contact(lower, above, hc));
  REQUIRE(contact(lower, above, hc, 2e-3));
  for (const auto& p : hc.points) CHECK(p.gap < 0);
  // Beside it, 1 cm apart in x: no contact at all.
  const Hull beside(box({1, 1, 1}, {1.01, 0, 0}));
  CHECK_FALSE(contact(lower, beside, hc));
}

TEST_CASE("hull separation: apart, touching, nested", "[contact][hulls]") {
  const Hull big(box({1, 1, 1}, {0, 0, 0}));
  const auto sep = [&](const Hull& other) { return detail::hull_separation(big.g, big.at(), other.g, other.at(), 0.0); };
  CHECK(sep(Hull(box({1, 1, 1}, {1.25, 0, 0}))) == Approx(0.25));
  CHECK(sep(Hull(box({0.5, 0.5, 0.5}, {0, 0, 1}))) == Approx(0.0).margin(1e-12));
  // A small box inside the big one (a chair under a desk's hull): it overlaps by at least its own size.
  CHECK(sep(Hull(box({0.2, 0.2, 0.2}, {0.1, 0.1, 0.3}))) < -0.19);
}

}  // namespace hull_pair_tests
