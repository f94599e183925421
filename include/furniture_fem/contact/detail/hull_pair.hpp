#pragma once
// Internal: two rigid bodies' hulls against each other, the reduced item-item geometry of rigid items
// (docs/contact/contact.md, "Rigid pairs by their hulls"). As box-box contact in rigid-body engines:
//  1. separating axes among the faces' normals of both hulls: the face whose plane the other hull
//     penetrates least is the reference face (none: apart);
//  2. the other hull's face most nearly opposed to it is the incident face;
//  3. the contact points: the incident face's corners inside the reference face, the points where its
//     edges enter and leave the reference face (Cyrus-Beck), and the reference face's corners inside
//     the incident face, each with its gap to the reference plane. Each is named by the corner or edge
//     that makes it, so that its friction history can follow it from step to step.
// Crossed edges (an edge of one hull across an edge of the other, neither face on the other) give no
// axis here: such a pair touches once a corner or face reaches the other hull.
// Users include furniture_fem/contact/room_contact.hpp, not this file.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/hull_pair.hpp is internal: include <furniture_fem/contact/room_contact.hpp>"
#endif
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "support_points.hpp"

namespace furniture_fem::detail {

// A contact point of two hulls, named by what makes it (the same name from step to step while the
// hulls keep their configuration, so that a friction history follows it).
enum class HullPointKind : int {
  corner = 0,     // a corner of the incident face inside the reference face: `id`
  entering = 1,   // where the incident edge id -> id2 enters the reference face
  leaving = 2,    // where it leaves it
  reference = 3,  // a corner `id` of the reference face inside the incident face, on the incident face
};
struct HullContactPoint {
  HullPointKind kind = HullPointKind::corner;
  int id = -1, id2 = -1;
  Vec3 x = Vec3::Zero();  // on the incident face
  double gap = 0;         // along the reference face's normal, less the contact distance (< 0: overlap)
};

struct HullPairContact {
  bool reference_on_a = true;  // the reference face is one of hull a's (b's points are incident)
  const SupportFace* reference = nullptr;
  const SupportFace* incident = nullptr;
  Vec3 normal = Vec3::Zero();  // the reference face's, out of its body
  std::vector<HullContactPoint> points;
};

namespace hull_pair {

struct Plane {
  Vec3 normal;
  Vec3 origin;
};

template <class Position>
Plane face_plane(const SupportFace& f, Position&& x) {
  const Vec3 x0 = x(f.frame[0]);
  return {(x(f.frame[1]) - x0).cross(x(f.frame[2]) - x0).normalized(), x0};
}

// The least signed distance of the vertices of `other` from a plane, less the contact distance.
template <class Position>
double separation(const Plane& p, const SupportGeometry& other, Position&& x, double distance) {
  double s = std::numeric_limits<double>::infinity();
  for (int v : other.vertices) s = std::min(s, p.normal.dot(x(v) - p.origin));
  return s - distance;
}

// A face's vertices in counter-clockwise order about `normal` (the geometry lists them ascending).
template <class Position>
void ordered_polygon(const SupportFace& f, Position&& x, const Vec3& normal, std::vector<int>& ids,
                     std::vector<Vec3>& xs) {
  Vec3 c = Vec3::Zero();
  for (int v : f.vertices) c += x(v);
  c /= static_cast<double>(f.vertices.size());
  const Vec3 u = normal.unitOrthogonal(), w = normal.cross(u);
  ids = f.vertices;
  std::vector<double> angle(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const Vec3 d = x(ids[k]) - c;
    angle[k] = std::atan2(w.dot(d), u.dot(d));
  }
  std::vector<std::size_t> order(ids.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return angle[i] < angle[j]; });
  std::vector<int> sorted;
  xs.clear();
  for (std::size_t k : order) sorted.push_back(ids[k]), xs.push_back(x(ids[k]));
  ids = std::move(sorted);
}

// A convex polygon (CCW about n) and the inward normals of its sides (in the plane normal to n).
struct Polygon {
  std::vector<int> ids;
  std::vector<Vec3> xs, inward;
  void set_sides(const Vec3& n) {
    inward.clear();
    for (std::size_t k = 0; k < xs.size(); ++k) inward.push_back(n.cross(xs[(k + 1) % xs.size()] - xs[k]).normalized());
  }
  // The least distance of p inside the sides (negative: outside one of them).
  double inside(const Vec3& p) const {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < xs.size(); ++k) d = std::min(d, inward[k].dot(p - xs[k]));
    return d;
  }
};

// Cyrus-Beck: the part [t0, t1] of the segment p0 -> p1 inside the polygon's sides (points within
// `tolerance` outside count as inside); false when none is.
inline bool clip_segment(const Polygon& poly, const Vec3& p0, const Vec3& p1, double tolerance, double& t0, double& t1) {
  t0 = 0, t1 = 1;
  for (std::size_t k = 0; k < poly.xs.size(); ++k) {
    const double d0 = poly.inward[k].dot(p0 - poly.xs[k]), d1 = poly.inward[k].dot(p1 - poly.xs[k]);
    if (d0 < -tolerance && d1 < -tolerance) return false;
    if (d0 < -tolerance) t0 = std::max(t0, d0 / (d0 - d1));
    else if (d1 < -tolerance) t1 = std::min(t1, d0 / (d0 - d1));
  }
  return t0 <= t1;
}

// Among the faces of `ref` (positions xr) against the hull `other` (positions xo): the face the other
// penetrates least (the largest separation, plus `bias` when comparing), if it beats `best`.
struct Axis {
  double separation = -std::numeric_limits<double>::infinity();
  double score = -std::numeric_limits<double>::infinity();
  const SupportFace* face = nullptr;
  Vec3 normal = Vec3::Zero();
};
template <class PR, class PO>
void best_axis(const SupportGeometry& ref, PR&& xr, const SupportGeometry& other, PO&& xo, double distance,
               double bias, Axis& best) {
  for (const auto& f : ref.faces) {
    const Plane p = face_plane(f, xr);
    const double s = separation(p, other, xo, distance);
    if (s + bias > best.score) best = {s, s + bias, &f, p.normal};
  }
}

}  // namespace hull_pair

// How far apart hulls a and b are (their largest separation along their faces' normals, less the
// contact distance; negative: they overlap at least that deep). +infinity when either is flat.
template <class PA, class PB>
double hull_separation(const SupportGeometry& a, PA&& xa, const SupportGeometry& b, PB&& xb, double distance) {
  if (a.faces.empty() || b.faces.empty()) return std::numeric_limits<double>::infinity();
  hull_pair::Axis best;
  hull_pair::best_axis(a, xa, b, xb, distance, 0.0, best);
  hull_pair::best_axis(b, xb, a, xa, distance, 0.0, best);
  return best.separation;
}

// The contact of hulls a and b (positions xa(i), xb(i) of their points now) whose surfaces touch at a
// distance `distance` apart (the members' half widths at centre lines, 0 at surfaces). False when a
// separating face is more than `margin` clear of the other hull. Ties go to a's faces, up to `bias`
// (so that a pair resting face on face keeps its reference from step to step).
template <class PA, class PB>
bool hull_pair_contact(const SupportGeometry& a, PA&& xa, const SupportGeometry& b, PB&& xb, double distance,
                       double margin, double bias, HullPairContact& out) {
  out.points.clear();
  if (a.faces.empty() || b.faces.empty()) return false;
  hull_pair::Axis best;
  hull_pair::best_axis(a, xa, b, xb, distance, bias, best);
  const SupportFace* face_a = best.face;
  hull_pair::best_axis(b, xb, a, xa, distance, 0.0, best);
  if (best.separation > margin) return false;
  const SupportFace* face = best.face;
  const Vec3 normal = best.normal;
  out.reference_on_a = face == face_a;
  out.reference = face;
  out.normal = normal;
  const SupportGeometry& inc = out.reference_on_a ? b : a;
  // Positions through one callable, whichever hull is which.
  const auto x_ref = [&](int i) -> Vec3 { return out.reference_on_a ? Vec3(xa(i)) : Vec3(xb(i)); };
  const auto x_inc = [&](int i) -> Vec3 { return out.reference_on_a ? Vec3(xb(i)) : Vec3(xa(i)); };
  out.incident = inc.faces.data();
  double most_opposed = 2;
  for (const auto& f : inc.faces) {
    const double c = hull_pair::face_plane(f, x_inc).normal.dot(normal);
    if (c < most_opposed) most_opposed = c, out.incident = &f;
  }
  // Both polygons counter-clockwise about the reference normal; the incident one's sides taken in its
  // plane's projection along that normal.
  hull_pair::Polygon ref, inc_poly;
  hull_pair::ordered_polygon(*out.reference, x_ref, normal, ref.ids, ref.xs);
  hull_pair::ordered_polygon(*out.incident, x_inc, normal, inc_poly.ids, inc_poly.xs);
  ref.set_sides(normal);
  inc_poly.set_sides(normal);
  constexpr double on_side = 1e-7;  // m: a corner this close outside a side counts as inside
  const Vec3 origin = ref.xs.front();
  const auto add = [&](HullPointKind kind, int id, int id2, const Vec3& x) {
    const double gap = normal.dot(x - origin) - distance;
    if (gap <= 0) out.points.push_back({kind, id, id2, x, gap});
  };
  const std::size_t n = inc_poly.xs.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 &p0 = inc_poly.xs[k], &p1 = inc_poly.xs[(k + 1) % n];
    const int i0 = inc_poly.ids[k], i1 = inc_poly.ids[(k + 1) % n];
    if (ref.inside(p0) >= -on_side) add(HullPointKind::corner, i0, -1, p0);
    double t0 = 0, t1 = 1;
    if (!hull_pair::clip_segment(ref, p0, p1, on_side, t0, t1)) continue;
    if (t0 > 0) add(HullPointKind::entering, i0, i1, p0 + t0 * (p1 - p0));
    if (t1 < 1) add(HullPointKind::leaving, i0, i1, p0 + t1 * (p1 - p0));
  }
  // The reference face's corners strictly inside the incident face (a small face on a large one that
  // is the reference): the incident face's point below each, along the normal.
  const Vec3 inc_normal = hull_pair::face_plane(*out.incident, x_inc).normal;
  const double along = normal.dot(inc_normal);
  if (std::abs(along) > 1e-6)
    for (std::size_t k = 0; k < ref.xs.size(); ++k) {
      const Vec3& r = ref.xs[k];
      const Vec3 on_incident = r - (inc_normal.dot(r - inc_poly.xs.front()) / along) * normal;
      if (inc_poly.inside(on_incident) > on_side) add(HullPointKind::reference, ref.ids[k], -1, on_incident);
    }
  return !out.points.empty();
}

}  // namespace furniture_fem::detail
