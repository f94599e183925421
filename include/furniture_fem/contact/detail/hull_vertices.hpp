#pragma once
// Internal: the vertices of the convex hull of a rigid body's nodes, the only nodes RoomContact tests
// against the floor and walls for such a body (docs/contact/contact.md, "Rigid bodies").
// Users include furniture_fem/contact/room_contact.hpp, not this file.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/hull_vertices.hpp is internal: include <furniture_fem/contact/room_contact.hpp>"
#endif
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_3.h>

#include <Eigen/Core>
#include <algorithm>
#include <iterator>
#include <vector>

#include "../../core/model.hpp"

namespace furniture_fem::detail {

// Which points are vertices of the convex hull of all of them (CGAL::extreme_points_3; exact
// predicates, so points on the hull's edges and faces are not vertices). A plane that a set of points
// touches first is touched at a vertex of their hull. Fewer than four points: all of them.
inline std::vector<char> hull_vertex_flags(const std::vector<Vec3>& points) {
  std::vector<char> is_vertex(points.size(), 1);
  if (points.size() < 4) return is_vertex;
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::vector<Kernel::Point_3> in, extreme;
  in.reserve(points.size());
  for (const Vec3& p : points) in.emplace_back(p.x(), p.y(), p.z());
  CGAL::extreme_points_3(in, std::back_inserter(extreme));
  std::sort(extreme.begin(), extreme.end());
  for (std::size_t i = 0; i < points.size(); ++i)
    is_vertex[i] = std::binary_search(extreme.begin(), extreme.end(), in[i]);  // the points are copied exactly
  return is_vertex;
}

}  // namespace furniture_fem::detail
