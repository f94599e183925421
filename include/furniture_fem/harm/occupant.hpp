#pragma once
// furniture_fem/harm/occupant.hpp: a person in the room (docs/harm/occupants.md): a body-sized
// vertical cylinder standing on the floor with a head on top, fixed to the floor (the table frame). An
// occupant is a sensor by default: it records what reaches it and does not push the furniture back; as
// a rigid obstacle (`obstacle`) its head and body are capsules the furniture's nodes are pushed out of.
//
//   Occupant           where, posture, sizes, and the impact forms of its head and body
//   OccupantZone       head (a sphere) or body (the cylinder below the head, as a capsule: a cylinder
//                      with rounded ends, so that a box's distance to it is a point-to-box distance)
//   zone_intrusion     how far an item's box reaches into a zone (m; <= 0: not touching)
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "impact_form.hpp"
#include "item_box.hpp"

namespace furniture_fem {

enum class Posture { standing, seated };
enum class OccupantZone { head, body };

inline std::string_view to_string(Posture p) { return p == Posture::standing ? "standing" : "seated"; }
inline std::string_view to_string(OccupantZone z) { return z == OccupantZone::head ? "head" : "body"; }

// Defaults by posture: an adult's stature and the top of a seated adult's head (m), a body radius from
// the shoulder breadth (about 0.45 m; seated, the knees forward make it wider).
struct PostureSizes {
  double height, body_radius;
};
inline PostureSizes posture_sizes(Posture p) {
  return p == Posture::standing ? PostureSizes{1.70, 0.20} : PostureSizes{1.30, 0.30};
}

struct Occupant {
  std::string name;
  Vec2 position = Vec2::Zero();  // on the floor, table axes (m)
  double floor_z = 0.0;          // m
  Posture posture = Posture::standing;
  double height = 1.70;          // m, floor to the top of the head
  double body_radius = 0.20;     // m
  double head_radius = 0.10;     // m
  ImpactForm head{4.5, 1.0e6};   // Hybrid III head's mass; a skull's stiffness (docs/harm/occupants.md)
  ImpactForm body{35.0, 1.0e5};  // an adult's trunk; a chosen stiffness (its verdicts do not use it)
  bool obstacle = false;         // a rigid obstacle (pushes the furniture back) rather than a sensor

  Vec3 head_centre() const { return Vec3(position.x(), position.y(), floor_z + height - head_radius); }
  // The body's axis, from the floor to the bottom of the head, as a capsule's segment.
  Vec3 body_bottom() const { return Vec3(position.x(), position.y(), floor_z + body_radius); }
  Vec3 body_top() const {
    return Vec3(position.x(), position.y(), floor_z + std::max(body_radius, height - 2 * head_radius - body_radius));
  }
  const ImpactForm& form(OccupantZone z) const { return z == OccupantZone::head ? head : body; }
};

// The number of occupant j's zone among the capsules of people standing as obstacles (the contact
// reports its forces as PairForce::capsule_id of it): 2 j for the head, 2 j + 1 for the body.
inline int occupant_capsule(int j, OccupantZone z) { return 2 * j + (z == OccupantZone::head ? 0 : 1); }

namespace detail {
// The signed distance from the segment [p, q] to a box (negative inside), by golden-section search: a
// convex set's signed distance is convex along a segment (to 1e-9 of the length). The general case.
inline double segment_box_signed_distance_search(const Vec3& p, const Vec3& q, const OrientedBox& box) {
  const auto at = [&](double s) { return box.signed_distance(p + s * (q - p)); };
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0, hi = 1, a = hi - phi * (hi - lo), b = lo + phi * (hi - lo), fa = at(a), fb = at(b);
  while (hi - lo > 1e-9) {
    if (fa <= fb) hi = b, b = a, fb = fa, a = hi - phi * (hi - lo), fa = at(a);
    else lo = a, a = b, fa = fb, b = lo + phi * (hi - lo), fb = at(b);
  }
  return std::min({at(0.0), at(1.0), at(0.5 * (lo + hi))});
}

// The squared distance from the segment [p, q] to a box, exactly: in the box's frame each coordinate's
// excess over the half size is linear in the segment's parameter between the points where it crosses a
// face, so the squared distance is a quadratic there, minimised in closed form on each piece (at most
// seven). 0 when the segment reaches the box.
inline double segment_box_squared_distance(const Vec3& p, const Vec3& q, const OrientedBox& box) {
  const Vec3 a = box.axes.transpose() * (p - box.centre), b = box.axes.transpose() * (q - p);
  std::array<double, 8> cuts;
  cuts.fill(2.0);  // unused entries sort to the end: the whole array is sorted (GCC cannot bound n)
  int n = 0;
  cuts[n++] = 0.0;
  for (int i = 0; i < 3; ++i)
    if (b[i] != 0)
      for (double face : {box.half[i], -box.half[i]}) {
        const double t = (face - a[i]) / b[i];
        if (t > 0 && t < 1) cuts[n++] = t;
      }
  cuts[n++] = 1.0;
  std::sort(cuts.begin(), cuts.end());
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k + 1 < n; ++k) {
    const double t0 = cuts[k], t1 = cuts[k + 1], tm = 0.5 * (t0 + t1);
    double ab = 0, bb = 0;  // the piece's f(t) = sum (alpha + beta t)^2
    Vec3 alpha = Vec3::Zero(), beta = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      const double v = a[i] + tm * b[i];
      if (v > box.half[i]) alpha[i] = a[i] - box.half[i], beta[i] = b[i];
      else if (v < -box.half[i]) alpha[i] = -a[i] - box.half[i], beta[i] = -b[i];
      ab += alpha[i] * beta[i], bb += beta[i] * beta[i];
    }
    const double t = bb > 0 ? std::clamp(-ab / bb, t0, t1) : t0;
    best = std::min(best, (alpha + t * beta).squaredNorm());
  }
  return best;
}

// The signed distance from the segment [p, q] to a box: exact when they are apart (the usual case), by
// search when the segment reaches into the box.
inline double segment_box_distance(const Vec3& p, const Vec3& q, const OrientedBox& box) {
  const double d2 = segment_box_squared_distance(p, q, box);
  return d2 > 0 ? std::sqrt(d2) : segment_box_signed_distance_search(p, q, box);
}
}  // namespace detail

// How far the box reaches into the zone: the zone's radius less the box's signed distance from its
// centre (the head) or axis (the body). Positive: touching; it keeps growing past the centre (a sensor is
// passed through), so a form pushed by an item keeps being pushed.
inline double zone_intrusion(const Occupant& o, OccupantZone z, const OrientedBox& box) {
  if (z == OccupantZone::head) return o.head_radius - box.signed_distance(o.head_centre());
  return o.body_radius - detail::segment_box_distance(o.body_bottom(), o.body_top(), box);
}

}  // namespace furniture_fem
