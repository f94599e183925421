// Contact geometry: closest points checked against independent references (dense search refined
// by golden section on a convex one-parameter function), and the degenerate cases exactly.
#include <catch2/catch.hpp>

#include <furniture_fem/contact/contact_geometry.hpp>

#include <random>

using namespace furniture_fem;
using Catch::Matchers::WithinAbs;

namespace geometry_tests {  // this file's own names (its group compiles files in batches)

namespace {

// Distance from a point to a segment by projection and clamping (the reference's building block).
double point_segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 d = b - a;
  const double dd = d.squaredNorm();
  double u = dd > 0 ? (p - a).dot(d) / dd : 0.0;
  u = std::clamp(u, 0.0, 1.0);
  return (p - (a + u * d)).norm();
}

// Reference for a point against a triangle: the projection when it falls inside, else the nearest
// edge. Independent of the Voronoi-region algorithm under test.
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double nn = n.squaredNorm();
  if (nn > 0) {
    const Vec3 q = p - (p - a).dot(n) / nn * n;
    const double w0 = (b - q).cross(c - q).dot(n) / nn, w1 = (c - q).cross(a - q).dot(n) / nn;
    if (w0 >= 0 && w1 >= 0 && 1 - w0 - w1 >= 0) return (p - q).norm();
  }
  return std::min({point_segment_distance(p, a, b), point_segment_distance(p, b, c), point_segment_distance(p, c, a)});
}

// Minimum of a convex function on [0, 1]: a dense scan, then golden section around the best sample.
template <class F>
double minimise_convex(F f) {
  const int samples = 2000;
  int best = 0;
  double fbest = f(0.0);
  for (int i = 1; i <= samples; ++i) {
    const double v = f(double(i) / samples);
    if (v < fbest) {
      fbest = v;
      best = i;
    }
  }
  double lo = std::max(0.0, double(best - 1) / samples), hi = std::min(1.0, double(best + 1) / samples);
  const double r = (std::sqrt(5.0) - 1) / 2;
  double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo), f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - r * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + r * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::min({fbest, f1, f2, f(lo), f(hi)});
}

double reference_segment_distance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  return minimise_convex([&](double s) { return point_segment_distance(a0 + s * (a1 - a0), b0, b1); });
}

void check_consistent(const SegmentSegmentClosest& c, const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1) {
  REQUIRE(c.s >= 0);
  REQUIRE(c.s <= 1);
  REQUIRE(c.t >= 0);
  REQUIRE(c.t <= 1);
  REQUIRE((c.p_WA - (a0 + c.s * (a1 - a0))).norm() < 1e-14);
  REQUIRE((c.p_WB - (b0 + c.t * (b1 - b0))).norm() < 1e-14);
  REQUIRE(std::abs(c.distance - (c.p_WA - c.p_WB).norm()) < 1e-15);
}

Vec3 random_point(std::mt19937_64& rng, double half = 1.0) {
  std::uniform_real_distribution<double> u(-half, half);
  return Vec3(u(rng), u(rng), u(rng));
}

}  // namespace

TEST_CASE("segment closest points match a dense search on 1000 random pairs", "[contact][geometry]") {
  std::mt19937_64 rng(20240611);
  double worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a0 = random_point(rng), a1 = random_point(rng), b0 = random_point(rng), b1 = random_point(rng);
    const auto c = closest_points_segment_segment(a0, a1, b0, b1);
    check_consistent(c, a0, a1, b0, b1);
    const double ref = reference_segment_distance(a0, a1, b0, b1);
    worst = std::max(worst, std::abs(c.distance - ref));
    REQUIRE_THAT(c.distance, WithinAbs(ref, 1e-9));
    // Swapping the segments gives the same distance.
    REQUIRE_THAT(closest_points_segment_segment(b0, b1, a0, a1).distance, WithinAbs(c.distance, 1e-12));
  }
  INFO("worst distance error " << worst);
  CHECK(worst < 1e-10);
}

TEST_CASE("nearly parallel segments stay exact", "[contact][geometry]") {
  // Angles from 1e-3 down to 1e-9 rad, where the line solution is ill-conditioned; the candidates
  // keep the distance exact, and below 1e-6 rad the parallel rule errs by at most overlap x angle.
  std::mt19937_64 rng(7);
  for (double angle : {1e-3, 1e-5, 1e-7, 1e-9}) {
    for (int i = 0; i < 50; ++i) {
      const Vec3 a0 = random_point(rng), a1 = random_point(rng);
      const Vec3 axis = (a1 - a0).unitOrthogonal();
      const Eigen::AngleAxisd rot(angle, axis);
      const Vec3 offset = 0.05 * random_point(rng);
      const Vec3 b0 = a0 + offset + 0.3 * (a1 - a0), b1 = b0 + rot * (a1 - a0);
      const auto c = closest_points_segment_segment(a0, a1, b0, b1);
      check_consistent(c, a0, a1, b0, b1);
      const double tol = c.parallel ? 1e-6 * (a1 - a0).norm() + 1e-12 : 1e-9;
      REQUIRE_THAT(c.distance, WithinAbs(reference_segment_distance(a0, a1, b0, b1), tol));
    }
  }
}

TEST_CASE("parallel, collinear and degenerate segments", "[contact][geometry]") {
  SECTION("parallel with overlap: midpoint of the overlap, symmetric") {
    const Vec3 a0(0, 0, 0), a1(2, 0, 0), b0(1, 1, 0), b1(3, 1, 0);
    const auto c = closest_points_segment_segment(a0, a1, b0, b1);
    CHECK(c.parallel);
    CHECK(c.s == 0.75);
    CHECK(c.t == 0.25);
    CHECK(c.p_WA == Vec3(1.5, 0, 0));
    CHECK(c.p_WB == Vec3(1.5, 1, 0));
    CHECK(c.distance == 1.0);
    const auto swapped = closest_points_segment_segment(b0, b1, a0, a1);
    CHECK(swapped.p_WA == c.p_WB);
    CHECK(swapped.p_WB == c.p_WA);
    // B reversed: same points, t measured from the other end.
    const auto reversed = closest_points_segment_segment(a0, a1, b1, b0);
    CHECK(reversed.p_WB == c.p_WB);
    CHECK(reversed.t == 0.75);
  }
  SECTION("one segment inside the other's span") {
    const auto c = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(1, 0, 0.5), Vec3(2, 0, 0.5));
    CHECK(c.p_WA == Vec3(1.5, 0, 0));
    CHECK(c.t == 0.5);
    CHECK(c.distance == 0.5);
  }
  SECTION("collinear overlapping: distance 0 at the overlap midpoint") {
    const auto c = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0));
    CHECK(c.distance == 0.0);
    CHECK(c.p_WA == Vec3(1.5, 0, 0));
    CHECK(c.p_WB == Vec3(1.5, 0, 0));
  }
  SECTION("collinear and parallel without overlap: nearest endpoints") {
    auto c = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0));
    CHECK(c.s == 1.0);
    CHECK(c.t == 0.0);
    CHECK(c.distance == 1.0);
    c = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(-1, 1, 0), Vec3(-3, 1, 0));
    CHECK(c.s == 0.0);
    CHECK(c.t == 0.0);
    CHECK_THAT(c.distance, WithinAbs(std::sqrt(2.0), 1e-15));
  }
  SECTION("zero-length segments") {
    auto c = closest_points_segment_segment(Vec3(0.5, 1, 0), Vec3(0.5, 1, 0), Vec3(0, 0, 0), Vec3(2, 0, 0));
    CHECK(c.s == 0.0);
    CHECK(c.t == 0.25);
    CHECK(c.distance == 1.0);
    c = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0), Vec3(3, 0, 0));
    CHECK(c.s == 1.0);
    CHECK(c.distance == 1.0);
    c = closest_points_segment_segment(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 4), Vec3(1, 2, 4));
    CHECK(c.distance == 1.0);
    CHECK(c.p_WA == Vec3(1, 2, 3));
  }
  SECTION("crossing beams: the common perpendicular") {
    const auto c = closest_points_segment_segment(Vec3(-1, 0, 0.04), Vec3(1, 0, 0.04), Vec3(0, -1, 0), Vec3(0, 1, 0));
    CHECK(c.s == 0.5);
    CHECK(c.t == 0.5);
    CHECK_THAT(c.distance, WithinAbs(0.04, 1e-15));
    CHECK(contact_normal(c, Vec3(2, 0, 0), Vec3(0, 2, 0)).isApprox(Vec3::UnitZ()));
  }
  SECTION("touching centre lines: normal from the directions, oriented by the previous one") {
    const auto c = closest_points_segment_segment(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0, -1, 0), Vec3(0, 1, 0));
    CHECK(c.distance == 0.0);
    const Vec3 n = contact_normal(c, Vec3(2, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, -1));
    CHECK(n.isApprox(Vec3(0, 0, -1)));
    const auto cp = closest_points_segment_segment(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0), Vec3(3, 0, 0));
    const Vec3 m = contact_normal(cp, Vec3(2, 0, 0), Vec3(2, 0, 0));
    CHECK_THAT(m.norm(), WithinAbs(1.0, 1e-15));
    CHECK_THAT(m.x(), WithinAbs(0.0, 1e-15));
  }
}

TEST_CASE("segments_apart_beyond only passes over pairs farther apart than the contact distance",
          "[contact][geometry]") {
  // The narrow phase skips a candidate pair when this says it is apart: it must never say so of a pair
  // within the distance (checked against the dense-search reference, which does not use the boxes),
  // over sizes from the paper's 50 mm elements to 2 m members, offsets from touching to 4 L, and a
  // third of the pairs parallel (members lying along each other). The sample must hold many pairs it
  // passes over and many within L, or the check says nothing.
  std::mt19937_64 rng(77);
  int within = 0, passed_over = 0;
  for (double size : {0.05, 0.3, 2.0}) {
    for (double L : {0.005, 0.02, 0.05}) {
      for (int i = 0; i < 300; ++i) {
        const Vec3 a0 = random_point(rng, size), a1 = a0 + random_point(rng, size);
        const Vec3 dir = i % 3 == 0 ? Vec3(a1 - a0) : random_point(rng, size);
        const double reach = 4 * L * std::uniform_real_distribution<double>(0, 1)(rng);
        const Vec3 b0 = a0 + std::uniform_real_distribution<double>(0, 1)(rng) * (a1 - a0) +
                        reach * random_point(rng, 1.0).normalized(),
                   b1 = b0 + dir;
        const double ref = reference_segment_distance(a0, a1, b0, b1);
        const bool skip = segments_apart_beyond(a0, a1, b0, b1, L);
        INFO("size " << size << ", L " << L << ", reference distance " << ref);
        within += ref <= L;
        passed_over += skip;
        if (skip) REQUIRE(ref > L);
        if (skip) REQUIRE(closest_points_segment_segment(a0, a1, b0, b1).distance > L);
      }
    }
  }
  INFO(passed_over << " passed over, " << within << " within L, of 2700 pairs");
  CHECK(passed_over > 200);
  CHECK(within > 200);
  SECTION("exactly at the contact distance, and a hair beyond it") {
    const Vec3 a0(0, 0, 0), a1(1, 0, 0), b0(0, 0.02, 0), b1(1, 0.02, 0);
    CHECK_FALSE(segments_apart_beyond(a0, a1, b0, b1, 0.02));
    CHECK_FALSE(segments_apart_beyond(a0, a1, b0, b1, 0.02 - 1e-10));  // within the slack: evaluated
    CHECK(segments_apart_beyond(a0, a1, b0, b1, 0.02 - 1e-6));
  }
}

TEST_CASE("node against a plane and a bounded rectangle", "[contact][geometry]") {
  SECTION("plane") {
    const Plane floor{Vec3(0, 0, 1), Vec3::UnitZ()};
    auto d = point_plane(Vec3(0.3, 0.2, 1.02), floor);
    CHECK_THAT(d.signed_distance, WithinAbs(0.02, 1e-15));
    CHECK(d.p_WF.isApprox(Vec3(0.3, 0.2, 1.0)));
    d = point_plane(Vec3(0.3, 0.2, 0.99), floor);
    CHECK_THAT(d.signed_distance, WithinAbs(-0.01, 1e-15));
    const Plane tilted{Vec3(1, 0, 0), Vec3(1, 1, 0).normalized()};
    d = point_plane(Vec3(2, 1, 5), tilted);
    CHECK_THAT(d.signed_distance, WithinAbs(2 / std::sqrt(2.0), 1e-15));
    CHECK_THAT((d.p_WF - tilted.p_WO).dot(tilted.n_W), WithinAbs(0.0, 1e-15));
  }
  SECTION("rectangle: inside, on the edge, outside") {
    const Rectangle wall{Vec3(1, 0, 0.5), Vec3(0, 0.5, 0), Vec3(0, 0, 0.5)};  // normal +x
    CHECK(wall.normal().isApprox(Vec3::UnitX()));
    auto d = point_rectangle(Vec3(1.02, 0.1, 0.3), wall);
    REQUIRE(d);
    CHECK_THAT(d->signed_distance, WithinAbs(0.02, 1e-15));
    CHECK(d->p_WF.isApprox(Vec3(1, 0.1, 0.3)));
    d = point_rectangle(Vec3(0.97, 0.5, 1.0), wall);  // on the corner, behind the plane
    REQUIRE(d);
    CHECK_THAT(d->signed_distance, WithinAbs(-0.03, 1e-15));
    CHECK_FALSE(point_rectangle(Vec3(1.01, 0.5001, 0.5), wall));
    CHECK_FALSE(point_rectangle(Vec3(1.01, 0.0, -0.01), wall));
    CHECK_FALSE(point_rectangle(Vec3(1, 0, 0), Rectangle{Vec3::Zero(), Vec3::UnitX(), Vec3::UnitX()}));
  }
}

TEST_CASE("point and segment against a triangle", "[contact][geometry]") {
  const Vec3 t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  SECTION("point regions") {
    CHECK(closest_point_on_triangle(Vec3(0.2, 0.3, 0.5), t0, t1, t2).p_WT.isApprox(Vec3(0.2, 0.3, 0)));
    CHECK(closest_point_on_triangle(Vec3(-1, -1, 0), t0, t1, t2).p_WT.isApprox(t0));
    CHECK(closest_point_on_triangle(Vec3(2, 2, 0), t0, t1, t2).p_WT.isApprox(Vec3(0.5, 0.5, 0)));
    const auto c = closest_point_on_triangle(Vec3(0.5, -2, 1), t0, t1, t2);
    CHECK(c.p_WT.isApprox(Vec3(0.5, 0, 0)));
    CHECK(c.barycentric.isApprox(Vec3(0.5, 0.5, 0)));
    // Degenerate triangle: its edges.
    CHECK_THAT(closest_point_on_triangle(Vec3(0.5, 1, 0), t0, t1, Vec3(2, 0, 0)).distance, WithinAbs(1.0, 1e-15));
  }
  SECTION("random points against the projection-or-edges reference") {
    std::mt19937_64 rng(3);
    for (int i = 0; i < 1000; ++i) {
      const Vec3 a = random_point(rng), b = random_point(rng), c = random_point(rng), p = random_point(rng, 2.0);
      const auto r = closest_point_on_triangle(p, a, b, c);
      REQUIRE_THAT(r.distance, WithinAbs(point_triangle_distance(p, a, b, c), 1e-12));
      REQUIRE((r.barycentric[0] * a + r.barycentric[1] * b + r.barycentric[2] * c - r.p_WT).norm() < 1e-12);
    }
  }
  SECTION("segment piercing, parallel above, beside an edge") {
    auto c = closest_points_segment_triangle(Vec3(0.2, 0.2, -1), Vec3(0.2, 0.2, 1), t0, t1, t2);
    CHECK(c.distance == 0.0);
    CHECK(c.s == 0.5);
    CHECK(c.p_WT.isApprox(Vec3(0.2, 0.2, 0)));
    c = closest_points_segment_triangle(Vec3(0.1, 0.2, 0.3), Vec3(0.3, 0.2, 0.3), t0, t1, t2);
    CHECK_THAT(c.distance, WithinAbs(0.3, 1e-15));
    c = closest_points_segment_triangle(Vec3(0.5, -0.5, -1), Vec3(0.5, -0.5, 1), t0, t1, t2);  // beside edge T0 T1
    CHECK_THAT(c.distance, WithinAbs(0.5, 1e-15));
    CHECK(c.p_WT.isApprox(Vec3(0.5, 0, 0)));
    CHECK_THAT(c.s, WithinAbs(0.5, 1e-15));
  }
  SECTION("random segments against the dense-search reference") {
    std::mt19937_64 rng(11);
    for (int i = 0; i < 300; ++i) {
      const Vec3 a = random_point(rng), b = random_point(rng), c = random_point(rng);
      const Vec3 p0 = random_point(rng, 1.5), p1 = random_point(rng, 1.5);
      const auto r = closest_points_segment_triangle(p0, p1, a, b, c);
      const double ref = minimise_convex([&](double s) { return point_triangle_distance(p0 + s * (p1 - p0), a, b, c); });
      REQUIRE_THAT(r.distance, WithinAbs(ref, 1e-9));
      REQUIRE((r.p_WA - (p0 + r.s * (p1 - p0))).norm() < 1e-12);
      REQUIRE_THAT((r.p_WA - r.p_WT).norm(), WithinAbs(r.distance, 1e-12));
    }
  }
}

}  // namespace geometry_tests
