#pragma once
// furniture_fem/contact/detail/cgal_adapter_impl.hpp: the definitions of contact/cgal_adapter.hpp that call
// CGAL: the broad phase's box intersection, the mesh obstacles' AABB tree and the convex hull. Included at the end of
// cgal_adapter.hpp when the contact module is used header-only; compiled once in
// src/contact/contact_compiled.cpp (furniture_fem::contact_compiled) otherwise. Not a header of its own.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/cgal_adapter_impl.hpp is internal: include <furniture_fem/contact/cgal_adapter.hpp>"
#endif
#include <CGAL/version.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/AABB_tree.h>
#if CGAL_VERSION_NR >= 1060000000
#include <CGAL/AABB_traits_3.h>
#include <CGAL/AABB_triangle_primitive_3.h>
#else
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_triangle_primitive.h>
#endif

namespace furniture_fem {

namespace detail {
namespace cgal_box = CGAL::Box_intersection_d;

// CGAL's box with an explicit id: the position of the element box in the caller's list, so the
// ids are unique and stable (CGAL's own ID_EXPLICIT uses a global counter).
class CgalElementBox : public cgal_box::Box_d<double, 3, cgal_box::ID_NONE> {
 public:
  using Base = cgal_box::Box_d<double, 3, cgal_box::ID_NONE>;
  using ID = std::size_t;
  CgalElementBox(const ElementBox& b, std::size_t index)
      : Base(CGAL::Bbox_3(b.lo.x(), b.lo.y(), b.lo.z(), b.hi.x(), b.hi.y(), b.hi.z())), index_(index) {}
  std::size_t id() const { return index_; }

 private:
  std::size_t index_;
};
}  // namespace detail

FFEM_CONTACT_DETECTION_INLINE void BroadPhase::pairs(std::span<const ElementBox> boxes, std::vector<std::pair<int, int>>& out) {
  // CGAL reorders the boxes it is given: the two sides' boxes, built from their indices.
  std::vector<detail::CgalElementBox> cgal_a, cgal_b;
  const auto to_cgal = [&](const std::vector<std::size_t>& set, std::vector<detail::CgalElementBox>& cgal) {
    cgal.clear();
    for (std::size_t i : set) cgal.emplace_back(boxes[i], i);
  };
  keys_.clear();
  group_by_body(boxes);
  body_pairs_tested_ = 0;
  const std::size_t nb = body_ids_.size();
  for (std::size_t a = 0; a < nb; ++a) {
    for (std::size_t b = a + 1; b < nb; ++b) {
      if (!body_box_[a].overlaps(body_box_[b])) continue;
      ++body_pairs_tested_;
      // Only elements that reach into the other body's box can meet it.
      collect(boxes, a, body_box_[b], set_a_);
      collect(boxes, b, body_box_[a], set_b_);
      if (set_a_.empty() || set_b_.empty()) continue;
      to_cgal(set_a_, cgal_a);
      to_cgal(set_b_, cgal_b);
      CGAL::box_intersection_d(cgal_a.begin(), cgal_a.end(), cgal_b.begin(), cgal_b.end(),
                               [&](const detail::CgalElementBox& x, const detail::CgalElementBox& y) {
                                 add(boxes[x.id()].element, boxes[y.id()].element);
                               },
                               cutoff);
    }
    if (same_body_pairs) {
      to_cgal(members_[a], cgal_a);
      CGAL::box_self_intersection_d(cgal_a.begin(), cgal_a.end(),
                                    [&](const detail::CgalElementBox& x, const detail::CgalElementBox& y) {
                                      if (!boxes[x.id()].shares_node(boxes[y.id()]))
                                        add(boxes[x.id()].element, boxes[y.id()].element);
                                    },
                                    cutoff);
    }
  }
  // Canonical order; each pair is packed into one 64-bit key so the sort compares integers.
  std::sort(keys_.begin(), keys_.end());
  out.resize(keys_.size());
  for (std::size_t k = 0; k < keys_.size(); ++k) out[k] = {unpack(keys_[k] >> 32), unpack(keys_[k] & 0xffffffffu)};
}

namespace detail {
struct CgalMeshTree {
  using Kernel = CGAL::Simple_cartesian<double>;
  using Triangle = Kernel::Triangle_3;
  using Point = Kernel::Point_3;
  using Iterator = std::vector<Triangle>::const_iterator;
#if CGAL_VERSION_NR >= 1060000000
  using Primitive = CGAL::AABB_triangle_primitive_3<Kernel, Iterator>;
  using Traits = CGAL::AABB_traits_3<Kernel, Primitive>;
#else
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
  using Traits = CGAL::AABB_traits<Kernel, Primitive>;
#endif
  using Tree = CGAL::AABB_tree<Traits>;

  std::vector<Triangle> triangles;  // the tree points into this vector: never resized after build
  std::vector<int> source;          // index of each kept triangle in the input mesh
  Tree tree;
  CGAL::Bbox_3 box;                 // of the whole mesh

  static Point point(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }
  static Vec3 vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
};
}  // namespace detail

FFEM_CONTACT_DETECTION_INLINE MeshObstacle::MeshObstacle(TriangleMesh mesh, std::string name) : name_(std::move(name)) {
  auto t = std::make_shared<detail::CgalMeshTree>();
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& tri = mesh.triangles[k];
    for (int v : tri)
      if (v < 0 || v >= static_cast<int>(mesh.vertices.size()))
        throw ModelError("mesh '" + name_ + "': triangle " + std::to_string(k) + " refers to vertex " +
                         std::to_string(v) + " of " + std::to_string(mesh.vertices.size()));
    for (int v : tri)
      if (!(mesh.vertices[v].cwiseAbs().maxCoeff() <= max_coordinate)) {
        const Vec3& p = mesh.vertices[v];
        throw ModelError("mesh '" + name_ + "': triangle " + std::to_string(k) + ", vertex " + std::to_string(v) +
                         " at (" + detail::coordinate_text(p.x()) + ", " + detail::coordinate_text(p.y()) + ", " +
                         detail::coordinate_text(p.z()) + ") lies farther than 1e6 m from the origin on an axis");
      }
    const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    if ((b - a).cross(c - a).squaredNorm() == 0) continue;
    t->triangles.emplace_back(t->point(a), t->point(b), t->point(c));
    t->source.push_back(static_cast<int>(k));
  }
  if (t->triangles.empty()) throw ModelError("mesh '" + name_ + "': no triangle of non-zero area");
  t->tree.rebuild(t->triangles.begin(), t->triangles.end());
  t->tree.accelerate_distance_queries();
  t->box = t->tree.bbox();
  mesh_ = std::move(mesh);
  tree_ = std::move(t);
}

FFEM_CONTACT_DETECTION_INLINE MeshClosestPoint MeshObstacle::closest(const Vec3& p_WQ) const {
  const auto pp = tree_->tree.closest_point_and_primitive(detail::CgalMeshTree::point(p_WQ));
  MeshClosestPoint c;
  c.p_WM = detail::CgalMeshTree::vec(pp.first);
  c.distance = (p_WQ - c.p_WM).norm();
  const auto k = static_cast<std::size_t>(pp.second - tree_->triangles.cbegin());
  c.triangle = tree_->source[k];
  const auto& tri = mesh_.triangles[c.triangle];
  c.n_W = (mesh_.vertices[tri[1]] - mesh_.vertices[tri[0]]).cross(mesh_.vertices[tri[2]] - mesh_.vertices[tri[0]]).normalized();
  return c;
}

FFEM_CONTACT_DETECTION_INLINE std::optional<MeshClosestPoint> MeshObstacle::closest_within(const Vec3& p_WQ, double d) const {
  const CGAL::Bbox_3 box(p_WQ.x() - d, p_WQ.y() - d, p_WQ.z() - d, p_WQ.x() + d, p_WQ.y() + d, p_WQ.z() + d);
  if (!CGAL::do_overlap(box, tree_->box) || !tree_->tree.do_intersect(box)) return std::nullopt;
  MeshClosestPoint c = closest(p_WQ);
  if (!(c.distance <= d)) return std::nullopt;
  return c;
}

FFEM_CONTACT_DETECTION_INLINE void MeshObstacle::segments_within(std::span<const MeshQuerySegment> segments, double d,
                                   std::vector<SegmentMeshContact>& out) const {
  out.clear();
  std::vector<detail::CgalMeshTree::Primitive::Id> hits;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Vec3 lo = segments[i].p_W0.cwiseMin(segments[i].p_W1) - Vec3::Constant(d);
    const Vec3 hi = segments[i].p_W0.cwiseMax(segments[i].p_W1) + Vec3::Constant(d);
    hits.clear();
    tree_->tree.all_intersected_primitives(CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()),
                                           std::back_inserter(hits));
    SegmentMeshContact best;
    for (const auto& id : hits) {
      const auto& tri = *id;
      const auto c = closest_points_segment_triangle(segments[i].p_W0, segments[i].p_W1, detail::CgalMeshTree::vec(tri[0]),
                                                     detail::CgalMeshTree::vec(tri[1]), detail::CgalMeshTree::vec(tri[2]));
      const int source = tree_->source[static_cast<std::size_t>(id - tree_->triangles.cbegin())];
      // Ties (a segment over a shared edge) go to the lower triangle index, for determinism.
      if (c.distance <= d && (best.segment < 0 || c.distance < best.closest.distance ||
                              (c.distance == best.closest.distance && source < best.triangle))) {
        best.segment = static_cast<int>(i);
        best.triangle = source;
        best.closest = c;
      }
    }
    if (best.segment >= 0) out.push_back(best);
  }
}

FFEM_CONTACT_DETECTION_INLINE std::size_t MeshObstacle::num_triangles() const { return tree_->triangles.size(); }

FFEM_CONTACT_DETECTION_INLINE std::vector<std::array<int, 3>> detail::convex_hull_triangles(const std::vector<Vec3>& P,
                                                                                         const std::vector<int>& points) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::vector<Point> cgal_points;
  for (int i : points) cgal_points.emplace_back(P[i].x(), P[i].y(), P[i].z());
  CGAL::Surface_mesh<Point> hull;
  if (points.size() >= 4) CGAL::convex_hull_3(cgal_points.begin(), cgal_points.end(), hull);
  std::vector<std::array<int, 3>> triangles;
  if (hull.number_of_faces() < 4) return triangles;
  // Hull vertices back to points: CGAL copies the points exactly.
  const auto index_of = [&](const Point& p) {
    return points[static_cast<std::size_t>(std::find(cgal_points.begin(), cgal_points.end(), p) - cgal_points.begin())];
  };
  for (auto f : hull.faces()) {
    std::array<int, 3> tri{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) tri[k++] = index_of(hull.point(v));
    triangles.push_back(tri);
  }
  return triangles;
}

}  // namespace furniture_fem
