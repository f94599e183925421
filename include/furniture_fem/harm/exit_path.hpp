#pragma once
// furniture_fem/harm/exit_path.hpp: an escape route's clear width on the floor plan, and the floor area
// items cover (docs/harm/harm.md, "Exits"). Pure geometry: no scene, no simulation.
//
//   path_stations     points along a polyline every `spacing` (and at every segment's ends), each with the
//                     unit normal of its segment
//   cross_section     the line through a station along its normal, cut to the room (the table's edge, the
//                     walls, an optional reach to each side), less what the obstacles' outlines cover:
//                     the clear width is the length of the widest free interval left that reaches into
//                     the exit's own band (within half its width of the path)
//   measure_exit      every station's cross-section and the narrowest one
//   union_area        the area of the union of convex outlines, exact (a sweep over x)
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "item_box.hpp"

namespace furniture_fem {

// Something on the plan a cross-section may hit: an item's outline (convex, counter-clockwise).
struct PlanObstacle {
  std::string name;
  std::vector<Vec2> outline;
};

// A wall's trace on the plan: the segment from a to b.
struct PlanWall {
  std::string name;
  Vec2 a = Vec2::Zero(), b = Vec2::Zero();
};

// What bounds an exit's cross-sections besides the obstacles: the table (an axis-aligned rectangle),
// the walls, and how far to each side of the path counts (none: up to a wall or the table's edge).
struct ExitRoom {
  Vec2 table_min = Vec2::Zero(), table_max = Vec2::Zero();
  std::vector<PlanWall> walls;
  std::optional<double> side_reach;  // m
};

struct PathStation {
  double s = 0;                    // arc length from the path's start (m)
  Vec2 at = Vec2::Zero();          // m
  Vec2 normal = Vec2::UnitY();     // unit, to the left of the path's direction
};

// One end of a free interval: an obstacle, a wall, the table's edge or the side reach.
struct SectionBound {
  enum class Kind { obstacle, wall, table_edge, reach } kind = Kind::table_edge;
  std::string name;  // the obstacle's or the wall's
};

// A cross-section's widest free interval [from, to] reaching into the exit's band, along the normal from
// the station (m; from <= 0 <= to need not hold: the path point itself may be covered), its bounds;
// `covered_by`: when no free interval reaches into the band, the obstacles that cut the band.
struct CrossSection {
  PathStation station;
  double clear_width = 0;  // to - from (m)
  double from = 0, to = 0;
  SectionBound low, high;
  std::vector<std::string> covered_by;
  // The obstacles that narrow it: those bounding its free interval, or covering it all.
  std::vector<std::string> narrowed_by() const {
    if (clear_width == 0) return covered_by;
    std::vector<std::string> names;
    for (const SectionBound* b : {&low, &high})
      if (b->kind == SectionBound::Kind::obstacle && std::find(names.begin(), names.end(), b->name) == names.end())
        names.push_back(b->name);
    return names;
  }
};

// Stations along the polyline: each segment divided into the fewest equal parts no longer than
// `spacing`, both its ends included (a corner is a station of both its segments, with each one's normal).
inline std::vector<PathStation> path_stations(const std::vector<Vec2>& path, double spacing = 0.05) {
  std::vector<PathStation> out;
  double s0 = 0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Vec2 d = path[i + 1] - path[i];
    const double length = d.norm();
    const Vec2 t = d / length;
    const int parts = std::max(1, static_cast<int>(std::ceil(length / spacing - 1e-9)));
    for (int k = 0; k <= parts; ++k) {
      const double f = double(k) / parts;
      out.push_back({s0 + f * length, path[i] + f * d, Vec2(-t.y(), t.x())});
    }
    s0 += length;
  }
  return out;
}

namespace detail {

// The parameters u where the line p + u n lies inside the convex counter-clockwise polygon, or none.
inline std::optional<std::pair<double, double>> line_in_convex(const Vec2& p, const Vec2& n, const std::vector<Vec2>& poly) {
  if (poly.size() < 3) return std::nullopt;
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 e = poly[(i + 1) % poly.size()] - poly[i];
    const Vec2 out(e.y(), -e.x());  // outward for counter-clockwise
    const double a = out.dot(n), b = out.dot(p - poly[i]);  // inside: b + u a <= 0
    if (a == 0) {
      if (b > 0) return std::nullopt;
    } else if (a > 0) {
      hi = std::min(hi, -b / a);
    } else {
      lo = std::max(lo, -b / a);
    }
  }
  if (!(lo < hi)) return std::nullopt;
  return std::make_pair(lo, hi);
}

// The nearest u > 0 where the ray p + u d leaves the rectangle or meets a wall, and what it meets.
inline std::pair<double, SectionBound> room_limit(const Vec2& p, const Vec2& d, const ExitRoom& room) {
  double u = std::numeric_limits<double>::infinity();
  SectionBound bound{SectionBound::Kind::table_edge, ""};
  for (int c = 0; c < 2; ++c) {
    if (d[c] > 0) u = std::min(u, (room.table_max[c] - p[c]) / d[c]);
    if (d[c] < 0) u = std::min(u, (room.table_min[c] - p[c]) / d[c]);
  }
  for (const PlanWall& w : room.walls) {
    const Vec2 e = w.b - w.a;
    const double den = d.x() * e.y() - d.y() * e.x();
    if (den == 0) continue;  // parallel: it never crosses the section
    const Vec2 q = w.a - p;
    const double at = (q.x() * e.y() - q.y() * e.x()) / den;  // along the ray
    const double along = (q.x() * d.y() - q.y() * d.x()) / den;  // along the wall, 0..1
    if (at > 1e-12 && at < u && along >= 0 && along <= 1) u = at, bound = {SectionBound::Kind::wall, w.name};
  }
  if (room.side_reach && *room.side_reach < u) u = *room.side_reach, bound = {SectionBound::Kind::reach, ""};
  return {u, bound};
}

}  // namespace detail

// The cross-section at a station: the room's extent along its normal, less the obstacles' intervals; its
// clear width is the widest free interval that reaches into the band |u| < band_half (the first of equal
// ones, from the right of the path). A gap that opens from within the band is one a person on the route
// can step into; one wholly outside it is another part of the room (across an open room it would read as
// the exit's width whatever lies on the path).
inline CrossSection cross_section(const PathStation& st, const ExitRoom& room, const std::vector<PlanObstacle>& obstacles,
                                  double band_half) {
  const auto [up, high_bound] = detail::room_limit(st.at, st.normal, room);
  const auto [down, low_bound] = detail::room_limit(st.at, -st.normal, room);
  struct Cut {
    double lo, hi;
    const std::string* name;
  };
  std::vector<Cut> cuts;
  for (const PlanObstacle& o : obstacles)
    if (const auto c = detail::line_in_convex(st.at, st.normal, o.outline); c && c->second > -down && c->first < up)
      cuts.push_back({c->first, c->second, &o.name});
  std::sort(cuts.begin(), cuts.end(), [](const Cut& a, const Cut& b) { return a.lo < b.lo; });
  CrossSection x;
  x.station = st;
  double edge = -down;  // the free interval starts here, bounded by `bound`
  SectionBound bound = low_bound;
  const auto consider = [&](double end, const SectionBound& end_bound) {
    if (end - edge > x.clear_width && end > -band_half && edge < band_half) x.clear_width = end - edge, x.from = edge, x.to = end, x.low = bound, x.high = end_bound;
  };
  for (const Cut& c : cuts) {
    if (c.lo > edge) consider(c.lo, {SectionBound::Kind::obstacle, *c.name});
    if (c.hi > edge) edge = c.hi, bound = {SectionBound::Kind::obstacle, *c.name};
  }
  if (up > edge) consider(up, high_bound);
  if (x.clear_width == 0)  // what covers the band
    for (const Cut& c : cuts)
      if (c.hi > -band_half && c.lo < band_half) x.covered_by.push_back(*c.name);
  return x;
}

// An exit measured: every station's cross-section, and the index of the narrowest (the first of equals).
struct ExitMeasure {
  std::vector<CrossSection> sections;
  std::size_t narrowest = 0;
  const CrossSection& at_narrowest() const { return sections[narrowest]; }
};

// `width`: the exit's required width (its band is half of it to each side of the path).
inline ExitMeasure measure_exit(const std::vector<Vec2>& path, double width, const ExitRoom& room,
                                const std::vector<PlanObstacle>& obstacles, double spacing = 0.05) {
  ExitMeasure m;
  for (const PathStation& st : path_stations(path, spacing)) {
    m.sections.push_back(cross_section(st, room, obstacles, 0.5 * width));
    if (m.sections.back().clear_width < m.sections[m.narrowest].clear_width) m.narrowest = m.sections.size() - 1;
  }
  return m;
}

// The area of a simple polygon, positive when counter-clockwise (the shoelace formula).
inline double polygon_area(const std::vector<Vec2>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec2& u = p[i];
    const Vec2& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return 0.5 * a;
}

namespace detail {

// The x where segments [a, b] and [c, d] cross, if they do (not parallel).
inline std::optional<double> crossing_x(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 r = b - a, s = d - c;
  const double den = r.x() * s.y() - r.y() * s.x();
  if (den == 0) return std::nullopt;
  const Vec2 q = c - a;
  const double t = (q.x() * s.y() - q.y() * s.x()) / den, u = (q.x() * r.y() - q.y() * r.x()) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return std::nullopt;
  return a.x() + t * r.x();
}

// The y interval of a convex polygon on the vertical line at x, or none.
inline std::optional<std::pair<double, double>> convex_at_x(const std::vector<Vec2>& poly, double x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % poly.size()];
    if ((a.x() - x) * (b.x() - x) > 0 || a.x() == b.x()) continue;
    const double y = a.y() + (x - a.x()) / (b.x() - a.x()) * (b.y() - a.y());
    lo = std::min(lo, y), hi = std::max(hi, y);
  }
  if (!(lo < hi)) return std::nullopt;
  return std::make_pair(lo, hi);
}

}  // namespace detail

// The area of the union of convex polygons (m^2 for outlines in m), exact up to rounding: between two
// consecutive breakpoints in x (every vertex, every crossing of two polygons' edges) each polygon's
// interval on a vertical line moves linearly and no two endpoints pass each other, so the union's
// length in y is linear in x and the midpoint rule integrates it exactly.
inline double union_area(const std::vector<std::vector<Vec2>>& polygons) {
  std::vector<double> xs;
  for (const auto& p : polygons)
    for (const Vec2& v : p) xs.push_back(v.x());
  for (std::size_t i = 0; i < polygons.size(); ++i)
    for (std::size_t j = i + 1; j < polygons.size(); ++j) {
      const auto& P = polygons[i];
      const auto& R = polygons[j];
      for (std::size_t a = 0; a < P.size(); ++a)
        for (std::size_t c = 0; c < R.size(); ++c)
          if (const auto x = detail::crossing_x(P[a], P[(a + 1) % P.size()], R[c], R[(c + 1) % R.size()])) xs.push_back(*x);
    }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  double area = 0;
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const double xm = 0.5 * (xs[k] + xs[k + 1]);
    std::vector<std::pair<double, double>> spans;
    for (const auto& p : polygons)
      if (const auto iv = detail::convex_at_x(p, xm)) spans.push_back(*iv);
    std::sort(spans.begin(), spans.end());
    double length = 0, top = -std::numeric_limits<double>::infinity();
    for (const auto& [lo, hi] : spans) {
      if (hi <= top) continue;
      length += hi - std::max(lo, top);
      top = hi;
    }
    area += length * (xs[k + 1] - xs[k]);
  }
  return area;
}

}  // namespace furniture_fem
