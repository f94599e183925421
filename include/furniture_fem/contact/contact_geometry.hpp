#pragma once
// furniture_fem/contact/contact_geometry.hpp: closest points for contact (Eigen only, no CGAL).
//
// Naming follows the frame-aware convention: p_WA is a point on A expressed in the world frame W
// (for the solver "world" is the shake-table frame), n_W a unit vector in W, d_A a direction of A.
// Every function states its degenerate cases in its comment; none divides by a length that can be
// zero. Included by contact_laws.hpp and contact.hpp; it has no state and no allocation.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>

#include "../core/model.hpp"

namespace furniture_fem {

namespace detail {
inline double clamp01(double x) { return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x); }

// A segment whose squared length is below this fraction of the squared size of the configuration
// (lengths and offset) is treated as a point: its direction carries no information.
inline constexpr double zero_length_ratio2 = 1e-24;

// Two segments count as parallel when sin^2 of their angle is below this (angle < 1 microradian).
// Treating them as parallel and taking the overlap midpoint then errs in distance by at most
// 1e-6 x the overlap length (5e-8 m for the paper's 50 mm elements), and keeps the contact point
// in the middle of two beams lying on each other instead of jumping between the overlap's ends.
inline constexpr double parallel_sin2 = 1e-12;
}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Segment against segment.

// Closest points of segment A (p_WA0 -> p_WA1) and segment B (p_WB0 -> p_WB1).
// s and t are the parameters on A and B in [0, 1]: p_WA = p_WA0 + s (p_WA1 - p_WA0), likewise p_WB.
struct SegmentSegmentClosest {
  double s = 0, t = 0;
  Vec3 p_WA = Vec3::Zero(), p_WB = Vec3::Zero();
  double distance = 0;
  bool parallel = false;  // the parallel rule below was used (also set for zero-length segments)
};

// Whether segments A and B are certainly more than `distance` apart: the distance of their bounding
// boxes, a lower bound of the distance of any point of A to any point of B, exceeds it by more than
// `slack` (the round-off of closest_points_segment_segment, about 1e-15 of the coordinates). When true,
// closest_points_segment_segment's distance exceeds `distance` too; a narrow phase may pass the pair
// over without it. (A pair with a non-finite point has no contact there either: its distance is NaN.)
inline bool segments_apart_beyond(const Vec3& p_WA0, const Vec3& p_WA1, const Vec3& p_WB0, const Vec3& p_WB1,
                                  double distance, double slack = 1e-9) {
  double gap2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double a_lo = std::min(p_WA0[i], p_WA1[i]), a_hi = std::max(p_WA0[i], p_WA1[i]);
    const double b_lo = std::min(p_WB0[i], p_WB1[i]), b_hi = std::max(p_WB0[i], p_WB1[i]);
    const double gap = std::max({a_lo - b_hi, b_lo - a_hi, 0.0});
    gap2 += gap * gap;
  }
  const double bound = distance + slack;
  return gap2 > bound * bound;
}

// Degenerate cases:
//  - both segments of zero length: s = t = 0 (the two points);
//  - one segment of zero length: that point against the other segment;
//  - parallel (sin^2 angle < detail::parallel_sin2), including collinear: when their projections
//    overlap, s is the midpoint of the overlap on A and t the projection of that point on B, so
//    swapping A and B gives the same contact point (symmetric); without overlap, the two nearest
//    endpoints;
//  - general position: the lines' common perpendicular when its feet lie inside both segments;
//    otherwise the best of the four "endpoint against the other segment" candidates. Taking the
//    minimum of the candidates (rather than clamping once) keeps the result exact for
//    nearly-parallel segments, where the line solution is ill-conditioned.
inline SegmentSegmentClosest closest_points_segment_segment(const Vec3& p_WA0, const Vec3& p_WA1,
                                                            const Vec3& p_WB0, const Vec3& p_WB1) {
  const Vec3 d_A = p_WA1 - p_WA0, d_B = p_WB1 - p_WB0, r = p_WA0 - p_WB0;
  const double aa = d_A.squaredNorm(), bb = d_B.squaredNorm(), ab = d_A.dot(d_B);
  const double ar = d_A.dot(r), br = d_B.dot(r);
  const double tiny = detail::zero_length_ratio2 * std::max({aa, bb, r.squaredNorm()});

  auto make = [&](double s, double t, bool parallel) {
    SegmentSegmentClosest c;
    c.s = s;
    c.t = t;
    c.p_WA = p_WA0 + s * d_A;
    c.p_WB = p_WB0 + t * d_B;
    c.distance = (c.p_WA - c.p_WB).norm();
    c.parallel = parallel;
    return c;
  };
  const bool a_is_point = aa <= tiny, b_is_point = bb <= tiny;
  if (a_is_point && b_is_point) return make(0, 0, true);
  if (a_is_point) return make(0, detail::clamp01(br / bb), true);   // min |r - t d_B|
  if (b_is_point) return make(detail::clamp01(-ar / aa), 0, true);  // min |r + s d_A|

  const double denom = aa * bb - ab * ab;  // = aa bb sin^2(angle) >= 0
  if (denom <= detail::parallel_sin2 * aa * bb) {
    // Parameters of B's endpoints projected on A's line; their interval meets [0, 1] or not.
    const double s_B0 = -ar / aa, s_B1 = (ab - ar) / aa;
    const double lo = std::max(0.0, std::min(s_B0, s_B1)), hi = std::min(1.0, std::max(s_B0, s_B1));
    if (lo <= hi) {
      const double s = 0.5 * (lo + hi);
      return make(s, detail::clamp01((r + s * d_A).dot(d_B) / bb), true);
    }
    if (std::max(s_B0, s_B1) < 0) return make(0, s_B0 > s_B1 ? 0.0 : 1.0, true);  // B lies before A
    return make(1, s_B0 < s_B1 ? 0.0 : 1.0, true);                                  // B lies after A
  }

  // Stationary point of |r + s d_A - t d_B|^2 (the common perpendicular of the lines); t follows
  // from s so the pair stays on the valley of the distance function even when s is inaccurate.
  // Inside the square it is the global minimum (the function is convex); when the segments are
  // well away from parallel (angle above ~0.01 rad) it is also accurate and returned at once.
  const double s_line = (ab * br - ar * bb) / denom;
  const double t_line = (br + s_line * ab) / bb;
  SegmentSegmentClosest best;
  bool have = false;
  if (s_line >= 0 && s_line <= 1 && t_line >= 0 && t_line <= 1) {
    best = make(s_line, t_line, false);
    if (denom > 1e-4 * aa * bb) return best;
    have = true;
  }
  const SegmentSegmentClosest candidates[4] = {
      make(0, detail::clamp01(br / bb), false),         // A0 against B
      make(1, detail::clamp01((br + ab) / bb), false),  // A1 against B
      make(detail::clamp01(-ar / aa), 0, false),        // B0 against A
      make(detail::clamp01((ab - ar) / aa), 1, false),  // B1 against A
  };
  for (const auto& c : candidates)
    if (!have || c.distance < best.distance) {
      best = c;
      have = true;
    }
  return best;
}

// Unit normal of a segment-segment contact, pointing from B towards A (a force along +n on A
// pushes the two apart). Degenerate cases: when the centre lines touch (distance below 1e-12 of
// the segments' size) the direction p_WA - p_WB is undefined; then the common normal of the two
// directions d_A x d_B is used, or for parallel segments any direction perpendicular to A. Its
// sign is arbitrary, so it is flipped to agree with previous_n_W when one is given (non-zero):
// a caller keeps the last normal of a pair so a pair passing through zero distance keeps pushing
// the same way.
inline Vec3 contact_normal(const SegmentSegmentClosest& c, const Vec3& d_A, const Vec3& d_B,
                           const Vec3& previous_n_W = Vec3::Zero()) {
  const double size = std::max({d_A.norm(), d_B.norm(), 1e-300});
  if (c.distance > 1e-12 * size) return (c.p_WA - c.p_WB) / c.distance;
  Vec3 n = d_A.cross(d_B);
  if (n.squaredNorm() <= 1e-24 * d_A.squaredNorm() * d_B.squaredNorm()) {
    const Vec3 d = d_A.squaredNorm() >= d_B.squaredNorm() ? d_A : d_B;
    n = d.squaredNorm() > 0 ? d.unitOrthogonal() : Vec3(Vec3::UnitZ());
  }
  n.normalize();
  if (previous_n_W.dot(n) < 0) n = -n;
  return n;
}

// ---------------------------------------------------------------------------------------------
// Point against plane and bounded rectangle.

// A rigid plane through p_WO with outward unit normal n_W: points with positive signed distance
// are outside (in front of the plane).
struct Plane {
  Vec3 p_WO = Vec3::Zero();
  Vec3 n_W = Vec3::UnitZ();
};

struct PointPlaneDistance {
  double signed_distance = 0;  // (p - p_WO) . n_W: negative when the point is behind the plane
  Vec3 p_WF = Vec3::Zero();    // foot of the perpendicular on the plane
  Vec3 n_W = Vec3::UnitZ();    // the plane's outward unit normal
};

// Signed distance of node N to the plane. n_W must be a unit vector (not renormalised here: the
// caller builds planes once, and a silent renormalisation would hide a wrong input).
inline PointPlaneDistance point_plane(const Vec3& p_WN, const Plane& plane) {
  PointPlaneDistance d;
  d.signed_distance = (p_WN - plane.p_WO).dot(plane.n_W);
  d.p_WF = p_WN - d.signed_distance * plane.n_W;
  d.n_W = plane.n_W;
  return d;
}

// A bounded rectangle (a wall panel, a table top seen as rigid): centre p_WC and two half-extent
// axes (vectors from the centre to the middle of two adjacent sides). The outward normal is
// half_u_W x half_v_W, normalised: order the axes so it points to the side where items live.
// The axes are expected orthogonal; non-orthogonal axes describe a parallelogram and the extent
// test below is then in the parallelogram's own (oblique) coordinates.
struct Rectangle {
  Vec3 p_WC = Vec3::Zero();
  Vec3 half_u_W = Vec3::UnitX(), half_v_W = Vec3::UnitY();
  Vec3 normal() const {
    const Vec3 n = half_u_W.cross(half_v_W);
    const double len = n.norm();
    return len > 0 ? Vec3(n / len) : Vec3::Zero();
  }
};

// Node N against a bounded rectangle: the plane distance when the node's projection lies within
// the rectangle (edges included); std::nullopt outside the extent (no contact) and for a
// degenerate rectangle (a zero or parallel axis). A node behind the plane is reported with a
// negative distance at any depth: the rectangle bounds a half-space slab, and a caller that must
// ignore nodes far behind a thin panel checks the depth itself.
inline std::optional<PointPlaneDistance> point_rectangle(const Vec3& p_WN, const Rectangle& rect) {
  const Vec3 n = rect.normal();
  if (n.squaredNorm() == 0) return std::nullopt;
  // In-plane coordinates from the 2x2 Gram system, so oblique axes are handled exactly.
  const Vec3 r = p_WN - rect.p_WC;
  const double uu = rect.half_u_W.squaredNorm(), vv = rect.half_v_W.squaredNorm(), uv = rect.half_u_W.dot(rect.half_v_W);
  const double ru = r.dot(rect.half_u_W), rv = r.dot(rect.half_v_W);
  const double det = uu * vv - uv * uv;  // > 0 since the normal is non-zero
  const double a = (ru * vv - rv * uv) / det, b = (rv * uu - ru * uv) / det;
  if (std::abs(a) > 1.0 || std::abs(b) > 1.0) return std::nullopt;
  return point_plane(p_WN, Plane{rect.p_WC, n});
}

// ---------------------------------------------------------------------------------------------
// Point against a capsule.

// A capsule: the points within `radius` of the segment [a, b] (a == b: a sphere). A person standing
// in the room as a rigid obstacle is two of them, a body and a head (harm/occupant.hpp).
struct Capsule {
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  double radius = 0;
};

// Node N against a capsule: the signed distance from its surface (negative inside), the foot on the
// surface and the outward normal there, as for a plane tangent to the capsule at the foot. A node on
// the axis itself has no normal: std::nullopt.
inline std::optional<PointPlaneDistance> point_capsule(const Vec3& p_WN, const Capsule& c) {
  const Vec3 ab = c.b - c.a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p_WN - c.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  const Vec3 r = p_WN - (c.a + s * ab);
  const double l = r.norm();
  if (!(l > 1e-12)) return std::nullopt;
  PointPlaneDistance d;
  d.n_W = r / l;
  d.signed_distance = l - c.radius;
  d.p_WF = p_WN - d.signed_distance * d.n_W;
  return d;
}

// ---------------------------------------------------------------------------------------------
// Point and segment against a triangle.

struct PointTriangleClosest {
  Vec3 p_WT = Vec3::Zero();         // closest point on the triangle
  Vec3 barycentric = Vec3::Zero();  // weights of T0, T1, T2 (sum 1)
  double distance = 0;
};

// Closest point on triangle T0 T1 T2 to point Q, by Voronoi regions (Ericson, Real-Time Collision
// Detection, 5.1.5). Degenerate triangle (zero area, including coincident vertices): the closest
// point on its three edges, since the Voronoi test would divide by the zero area.
inline PointTriangleClosest closest_point_on_triangle(const Vec3& p_WQ, const Vec3& p_WT0, const Vec3& p_WT1,
                                                      const Vec3& p_WT2) {
  auto result = [&](double w0, double w1, double w2) {
    PointTriangleClosest c;
    c.barycentric = Vec3(w0, w1, w2);
    c.p_WT = w0 * p_WT0 + w1 * p_WT1 + w2 * p_WT2;
    c.distance = (p_WQ - c.p_WT).norm();
    return c;
  };
  const Vec3 e01 = p_WT1 - p_WT0, e02 = p_WT2 - p_WT0;
  const double scale2 = std::max({e01.squaredNorm(), e02.squaredNorm(), (p_WT2 - p_WT1).squaredNorm()});
  if (e01.cross(e02).squaredNorm() <= detail::zero_length_ratio2 * scale2 * scale2) {
    PointTriangleClosest best;
    bool have = false;
    const Vec3* v[3] = {&p_WT0, &p_WT1, &p_WT2};
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = *v[k];
      const Vec3& b = *v[(k + 1) % 3];
      const Vec3 d = b - a;
      const double dd = d.squaredNorm();
      const double u = dd > 0 ? detail::clamp01((p_WQ - a).dot(d) / dd) : 0.0;
      Vec3 w = Vec3::Zero();
      w[k] = 1 - u;
      w[(k + 1) % 3] += u;
      const auto c = result(w[0], w[1], w[2]);
      if (!have || c.distance < best.distance) {
        best = c;
        have = true;
      }
    }
    return best;
  }
  const Vec3 q0 = p_WQ - p_WT0;
  const double d1 = e01.dot(q0), d2 = e02.dot(q0);
  if (d1 <= 0 && d2 <= 0) return result(1, 0, 0);  // vertex T0 region
  const Vec3 q1 = p_WQ - p_WT1;
  const double d3 = e01.dot(q1), d4 = e02.dot(q1);
  if (d3 >= 0 && d4 <= d3) return result(0, 1, 0);  // vertex T1 region
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {  // edge T0 T1
    const double u = d1 / (d1 - d3);
    return result(1 - u, u, 0);
  }
  const Vec3 q2 = p_WQ - p_WT2;
  const double d5 = e01.dot(q2), d6 = e02.dot(q2);
  if (d6 >= 0 && d5 <= d6) return result(0, 0, 1);  // vertex T2 region
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {  // edge T0 T2
    const double w = d2 / (d2 - d6);
    return result(1 - w, 0, w);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {  // edge T1 T2
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return result(0, 1 - w, w);
  }
  const double inv = 1.0 / (va + vb + vc);  // interior: the projection on the plane
  const double v = vb * inv, w = vc * inv;
  return result(1 - v - w, v, w);
}

struct SegmentTriangleClosest {
  double s = 0;                     // parameter on the segment, in [0, 1]
  Vec3 p_WA = Vec3::Zero();         // closest point on the segment
  Vec3 p_WT = Vec3::Zero();         // closest point on the triangle
  Vec3 barycentric = Vec3::Zero();  // of p_WT in the triangle
  double distance = 0;
};

// Closest points of segment A (a capsule of radius r around it touches the triangle when
// distance <= r, with penetration r - distance) and triangle T0 T1 T2.
// Cases: the segment pierces the triangle -> distance 0 at the piercing point; otherwise the
// minimum over "an endpoint against the triangle" and "the segment against an edge", which covers
// every configuration of two disjoint convex sets. A segment lying in the triangle's plane is
// covered by the candidates (an endpoint inside gives 0, crossing an edge gives 0). A zero-length
// segment is a point; a degenerate triangle reduces to its edges.
inline SegmentTriangleClosest closest_points_segment_triangle(const Vec3& p_WA0, const Vec3& p_WA1, const Vec3& p_WT0,
                                                              const Vec3& p_WT1, const Vec3& p_WT2) {
  const Vec3 d_A = p_WA1 - p_WA0;
  const Vec3 n = (p_WT1 - p_WT0).cross(p_WT2 - p_WT0);
  const double nn = n.squaredNorm();
  if (nn > 0) {
    const double h0 = (p_WA0 - p_WT0).dot(n), h1 = (p_WA1 - p_WT0).dot(n);
    if ((h0 < 0 && h1 > 0) || (h0 > 0 && h1 < 0)) {
      const double s = h0 / (h0 - h1);
      const Vec3 x = p_WA0 + s * d_A;
      // Barycentric coordinates by signed sub-areas; inside when none is negative.
      const double w0 = (p_WT1 - x).cross(p_WT2 - x).dot(n) / nn;
      const double w1 = (p_WT2 - x).cross(p_WT0 - x).dot(n) / nn;
      const double w2 = 1.0 - w0 - w1;
      if (w0 >= 0 && w1 >= 0 && w2 >= 0) {
        SegmentTriangleClosest c;
        c.s = s;
        c.p_WA = c.p_WT = x;
        c.barycentric = Vec3(w0, w1, w2);
        c.distance = 0;
        return c;
      }
    }
  }
  SegmentTriangleClosest best;
  bool have = false;
  auto consider = [&](const SegmentTriangleClosest& c) {
    if (!have || c.distance < best.distance) {
      best = c;
      have = true;
    }
  };
  for (int k = 0; k < 2; ++k) {  // endpoints against the triangle
    const Vec3& p = k == 0 ? p_WA0 : p_WA1;
    const auto pt = closest_point_on_triangle(p, p_WT0, p_WT1, p_WT2);
    SegmentTriangleClosest c;
    c.s = k;
    c.p_WA = p;
    c.p_WT = pt.p_WT;
    c.barycentric = pt.barycentric;
    c.distance = pt.distance;
    consider(c);
  }
  const Vec3* v[3] = {&p_WT0, &p_WT1, &p_WT2};
  for (int k = 0; k < 3; ++k) {  // the segment against each edge
    const auto ss = closest_points_segment_segment(p_WA0, p_WA1, *v[k], *v[(k + 1) % 3]);
    SegmentTriangleClosest c;
    c.s = ss.s;
    c.p_WA = ss.p_WA;
    c.p_WT = ss.p_WB;
    c.barycentric = Vec3::Zero();
    c.barycentric[k] = 1 - ss.t;
    c.barycentric[(k + 1) % 3] += ss.t;
    c.distance = ss.distance;
    consider(c);
  }
  return best;
}

}  // namespace furniture_fem
