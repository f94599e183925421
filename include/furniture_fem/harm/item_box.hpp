#pragma once
// furniture_fem/harm/item_box.hpp: an item's outer box where the item is now (docs/harm/harm.md), the
// geometry occupants and exits see: what can strike a person or cover a path.
//
//   OrientedBox   centre, axes (columns: the item's width, depth and height directions), half sizes
//   item_box      the item's box moved by its body's best rigid motion (rotation Q about the nodes'
//                 centroid, which moved from Xc to xc): exact for a rigid item, the best rigid fit for a
//                 flexible one
//   plan_outline  the box's shadow on the floor: the convex hull of its corners seen from above
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include "../core/model.hpp"
#include "../furniture/furniture.hpp"

namespace furniture_fem {

using Vec2 = Eigen::Vector2d;

struct OrientedBox {
  Vec3 centre = Vec3::Zero();
  Mat3 axes = Mat3::Identity();  // columns: unit vectors along the half sizes
  Vec3 half = Vec3::Zero();      // m

  std::array<Vec3, 8> corners() const {
    std::array<Vec3, 8> c;
    for (int i = 0; i < 8; ++i) {
      const Vec3 s((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
      c[i] = centre + axes * s.cwiseProduct(half);
    }
    return c;
  }
  // The point of the box (surface or inside) nearest to p.
  Vec3 closest_point(const Vec3& p) const {
    const Vec3 local = axes.transpose() * (p - centre);
    return centre + axes * local.cwiseMax(-half).cwiseMin(half);
  }
  // Distance from p to the box; 0 inside it.
  double distance(const Vec3& p) const { return (p - closest_point(p)).norm(); }
  // The same outside; inside, minus the depth below the nearest face (convex in p, as the box is).
  double signed_distance(const Vec3& p) const {
    const Vec3 depth = half - (axes.transpose() * (p - centre)).cwiseAbs();
    return depth.minCoeff() >= 0 ? -depth.minCoeff() : distance(p);
  }
};

// The item's box as placed (at t = 0, before any motion).
inline OrientedBox placed_box(const ItemInfo& item) {
  OrientedBox b;
  b.centre = item.to_world(Vec3(0.0, 0.0, 0.5 * item.size.z()));
  b.axes = item.R;
  b.half = 0.5 * item.size;
  return b;
}

// The item's box after its body's rigid motion: rotation Q about the nodes' centroid, from Xc to xc.
inline OrientedBox item_box(const ItemInfo& item, const Mat3& Q, const Vec3& Xc, const Vec3& xc) {
  OrientedBox b = placed_box(item);
  b.centre = Q * (b.centre - Xc) + xc;
  b.axes = Q * b.axes;
  return b;
}

// The convex hull of points in the plane, counter-clockwise, without repeated or collinear points
// (Andrew's monotone chain: a few lines, where CGAL's hull would cost every unit that shows a plan).
inline std::vector<Vec2> convex_hull_2d(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

// The box's outline on the floor plan (x, y), counter-clockwise.
inline std::vector<Vec2> plan_outline(const OrientedBox& box) {
  std::vector<Vec2> pts;
  for (const Vec3& c : box.corners()) pts.emplace_back(c.x(), c.y());
  return convex_hull_2d(std::move(pts));
}

}  // namespace furniture_fem
