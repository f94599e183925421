#pragma once
// Internal: the reduced contact geometry of a rigid body against planes (docs/contact/contact.md,
// "Rigid bodies"): the vertices of the convex hull of its points, and the hull's flat faces, each with
// the number of the body's nodes lying on it. A plane meets a rigid body first at a hull vertex; when a
// face lies on the plane, its vertices stand for every node of the face, each with an equal share.
// The points are the nodes (support_geometry: contact at the members' centre lines), or the corners
// of a cube of half the member width around each node (surface_support_geometry: contact at the
// members' surfaces); the geometry names them by their index in a list of positions.
// Users include furniture_fem/contact/room_contact.hpp, not this file.
#ifndef FURNITURE_FEM_CONTACT_INTERNAL
#error "furniture_fem/contact/detail/support_points.hpp is internal: include <furniture_fem/contact/room_contact.hpp>"
#endif
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

#include "../../core/dense_kernels.hpp"
#include "../../core/model.hpp"
#include "../cgal_adapter.hpp"

namespace furniture_fem::detail {

// A flat face of the hull: three of its vertex nodes in outward order ((x1 - x0) x (x2 - x0) points out
// of the body), all its vertex nodes, and the share each of them takes when the face rests on a plane.
struct SupportFace {
  std::array<int, 3> frame{};
  std::vector<int> vertices;
  double share = 1;  // nodes on the face / its vertices
};

struct SupportGeometry {
  std::vector<int> vertices;  // hull-vertex nodes, ascending; every node of a degenerate (flat) body
  std::vector<SupportFace> faces;

  // The face that looks most directly into a plane of unit normal n (x(i): point i's position now).
  template <class Position>
  const SupportFace* face_towards(Position&& x, const Vec3& n) const {
    const SupportFace* best = nullptr;
    double best_cos = -2;
    for (const auto& f : faces) {
      const Vec3 out = (x(f.frame[1]) - x(f.frame[0])).cross(x(f.frame[2]) - x(f.frame[0]));
      const double c = -out.dot(n) / out.norm();
      if (c > best_cos) best_cos = c, best = &f;
    }
    return best;
  }
};

namespace support {
using Points = std::vector<Vec3>;  // positions, by the index the geometry names them with

inline Vec3 unit_normal(const Points& P, const std::array<int, 3>& t) {
  return (P[t[1]] - P[t[0]]).cross(P[t[2]] - P[t[0]]).normalized();
}

// The hull's triangles (as node triples) merged into flat faces by their planes, largest triangle
// first: a face's plane is its largest triangle's, and a triangle joins the first face whose plane holds
// its three nodes. Comparing normals instead split faces: CGAL's triangulation of a flat face (which
// follows the nodes' order and the heap) can hold a sliver between nodes in line to round-off, whose
// normal is all round-off; it became a face of its own, with a share of a hundred nodes on each of its
// three vertices, in some processes and not in others.
inline std::vector<SupportFace> merge_into_faces(const Points& P, std::vector<std::array<int, 3>> tris,
                                                 std::vector<std::pair<Vec3, double>>& planes) {
  constexpr double on_plane = 1e-6;  // m
  const auto X = [&](int n) -> const Vec3& { return P[n]; };
  const auto area2 = [&](const std::array<int, 3>& t) { return (X(t[1]) - X(t[0])).cross(X(t[2]) - X(t[0])).norm(); };
  const auto sorted = [](std::array<int, 3> t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::sort(tris.begin(), tris.end(), [&](const auto& p, const auto& q) {
    const double ap = area2(p), aq = area2(q);
    return ap != aq ? ap > aq : sorted(p) < sorted(q);
  });
  std::vector<SupportFace> faces;
  planes.clear();  // per face: unit normal, offset
  for (const auto& tri : tris) {
    std::size_t k = 0;
    for (; k < faces.size(); ++k) {
      const Vec3& normal = planes[k].first;  // not a structured binding: clang 14 cannot capture those
      const double offset = planes[k].second;
      if (std::all_of(tri.begin(), tri.end(), [&](int n) { return std::abs(normal.dot(X(n)) - offset) < on_plane; }))
        break;
    }
    if (k == faces.size()) {  // a new face; its vertices are its corners (face_corners)
      const Vec3 normal = unit_normal(P, tri);
      faces.push_back(SupportFace{tri, {}, 1});
      planes.emplace_back(normal, normal.dot(X(tri[0])));
    }
  }
  return faces;
}

// A face's corners: the convex polygon of the body's nodes on its plane, nodes in line with their
// neighbours (to 1e-9 m) left out. CGAL keeps or drops a node that lies on a hull edge to round-off
// (an item turned by a yaw) depending on the nodes' order and the heap; the corners do not. The
// polygon is taken in the plane fitted to those nodes (least squares), so its basis, too, is the same
// to the bit whichever hull triangle defined the face.
inline std::vector<int> face_corners(const Points& P, const std::vector<int>& sorted_nodes, const Vec3& normal,
                                     double offset) {
  constexpr double on_plane = 1e-6, in_line = 1e-9;  // m
  const auto X = [&](int n) -> const Vec3& { return P[n]; };
  std::vector<int> on;
  for (int n : sorted_nodes)
    if (std::abs(normal.dot(X(n)) - offset) < on_plane) on.push_back(n);
  Vec3 c = Vec3::Zero();
  for (int n : on) c += X(n);
  c /= static_cast<double>(on.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (int n : on) cov += (X(n) - c) * (X(n) - c).transpose();
  const Vec3 fit = detail::smallest_eigenvector(cov);
  const Vec3 u = fit.unitOrthogonal(), v = fit.cross(u);
  struct Corner {
    double x, y;
    int node;
  };
  std::vector<Corner> pts;
  for (int n : on) pts.push_back({u.dot(X(n) - c), v.dot(X(n) - c), n});
  std::sort(pts.begin(), pts.end(), [](const Corner& a, const Corner& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.node < b.node;
  });
  // Andrew's monotone chain; a node within in_line of the line from its predecessor to its successor
  // is not a corner.
  const auto keeps = [&](const Corner& o, const Corner& a, const Corner& b) {
    const double cross = (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    return cross > in_line * std::hypot(b.x - o.x, b.y - o.y);
  };
  std::vector<Corner> hull;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t base = hull.size();
    for (const Corner& p : pts) {
      while (hull.size() >= base + 2 && !keeps(hull[hull.size() - 2], hull.back(), p)) hull.pop_back();
      hull.push_back(p);
    }
    hull.pop_back();  // the chain's last point starts the other chain
    std::reverse(pts.begin(), pts.end());
  }
  std::vector<int> corners;
  for (const Corner& p : hull) corners.push_back(p.node);
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return corners;
}

// A face in a form that does not depend on how the hull was triangulated or listed: its vertices
// ascending; its frame the two smallest vertices and the smallest next one not in line with them,
// ordered so that the frame's normal points out as before.
inline void canonical_frame(const Points& P, SupportFace& f) {
  const Vec3 out = unit_normal(P, f.frame);
  std::sort(f.vertices.begin(), f.vertices.end());
  const auto X = [&](int n) -> const Vec3& { return P[n]; };
  const int a = f.vertices[0], b = f.vertices[1];
  for (std::size_t k = 2; k < f.vertices.size(); ++k) {
    const int c = f.vertices[k];
    const Vec3 n = (X(b) - X(a)).cross(X(c) - X(a));
    if (n.norm() <= 1e-9 * (X(b) - X(a)).squaredNorm()) continue;  // in line with a and b
    f.frame = n.dot(out) > 0 ? std::array<int, 3>{a, b, c} : std::array<int, 3>{a, c, b};
    return;
  }
}

// Each face's share: the body's nodes on its plane (a member's nodes lie on it to round-off) per
// vertex. A node is on it when one of its points is (owner: the node of each point).
inline void set_shares(const Points& P, const std::vector<int>& points, const std::vector<int>& owner,
                       std::vector<SupportFace>& faces) {
  constexpr double on_plane = 1e-6;  // m
  for (auto& f : faces) {
    const Vec3 normal = unit_normal(P, f.frame);
    const double offset = normal.dot(P[f.frame[0]]);
    std::vector<int> on;
    for (int i : points)
      if (std::abs(normal.dot(P[i]) - offset) < on_plane) on.push_back(owner[i]);
    std::sort(on.begin(), on.end());
    const auto on_face = std::unique(on.begin(), on.end()) - on.begin();
    f.share = double(on_face) / double(f.vertices.size());
  }
}
}  // namespace support

// The hull of points P[i], i in `points` (CGAL::convex_hull_3); owner[i]: the node point i belongs to.
inline SupportGeometry hull_geometry(const support::Points& P, const std::vector<int>& points, const std::vector<int>& owner) {
  SupportGeometry g;
  // CGAL's listing of the hull depends on the order of the points and on where its data lie in memory
  // (a process's heap layout), and so does the triangulation of a flat face. Taken as listed, the
  // faces' frames (hence their normals, to round-off) and the order of their vertices changed from
  // one process to another, and a chaotic run with them. So each face is put in a canonical form.
  std::vector<std::array<int, 3>> triangles = convex_hull_triangles(P, points);
  if (triangles.empty()) {  // flat or too few points: no hull to reduce to
    g.vertices = points;
    std::sort(g.vertices.begin(), g.vertices.end());
    return g;
  }
  std::vector<std::pair<Vec3, double>> planes;
  g.faces = support::merge_into_faces(P, std::move(triangles), planes);
  std::vector<int> sorted_points = points;
  std::sort(sorted_points.begin(), sorted_points.end());
  for (std::size_t k = 0; k < g.faces.size(); ++k) {
    g.faces[k].vertices = support::face_corners(P, sorted_points, planes[k].first, planes[k].second);
    g.vertices.insert(g.vertices.end(), g.faces[k].vertices.begin(), g.faces[k].vertices.end());
  }
  // The hull's vertices: the faces' corners.
  std::sort(g.vertices.begin(), g.vertices.end());
  g.vertices.erase(std::unique(g.vertices.begin(), g.vertices.end()), g.vertices.end());
  for (auto& f : g.faces) support::canonical_frame(P, f);
  std::sort(g.faces.begin(), g.faces.end(), [](const SupportFace& a, const SupportFace& b) { return a.frame < b.frame; });
  support::set_shares(P, points, owner, g.faces);
  return g;
}

// The hull of a body's nodes at their initial positions: contact at the members' centre lines. The
// nodes are numbered by their rank among the body's node ids (not by the ids, which would size the
// positions by the whole model and set up a room of n items in n^2), and the ids put back after: ranks
// keep the ids' order, so the hull's canonical form is the same to the bit.
inline SupportGeometry support_geometry(const Model& model, const std::vector<int>& nodes) {
  std::vector<int> ids = nodes;
  std::sort(ids.begin(), ids.end());
  const auto rank = [&](int n) { return static_cast<int>(std::lower_bound(ids.begin(), ids.end(), n) - ids.begin()); };
  support::Points P(ids.size());
  std::vector<int> owner(ids.size()), points;
  for (std::size_t k = 0; k < ids.size(); ++k) P[k] = model.node(ids[k]).X, owner[k] = static_cast<int>(k);
  for (int n : nodes) points.push_back(rank(n));
  SupportGeometry g = hull_geometry(P, points, owner);
  for (int& i : g.vertices) i = ids[i];
  for (auto& f : g.faces) {
    for (int& i : f.vertices) i = ids[i];
    for (int& i : f.frame) i = ids[i];
  }
  return g;
}

// A point of a body's surface geometry: its node, and its offset from the node in the node's initial
// frame (the offset turns with the node).
struct SurfacePoint {
  int node = -1;
  Vec3 arm0 = Vec3::Zero();

  // Member by member in checkpoints (core/checkpoint.hpp): `node` is followed by padding bytes.
  template <class Self, class Archive>
    requires std::is_same_v<std::remove_const_t<Self>, SurfacePoint>
  friend void transfer_state(Self& s, Archive& ar) {
    ar(s.node, s.arm0);
  }
};

// The axes of the cube around each node (surface contact): the first member's axis and the first one
// across it (a frame's corner: the item's axes, at any yaw); a node inside a straight member those of a
// node along it with a member across; a node of one straight line, its section's axes; a node of no
// member, the table's. One matrix per node of the model, its columns the axes.
inline std::vector<Mat3> cube_axes(const Model& model) {
  std::vector<Mat3> axes(static_cast<std::size_t>(model.num_nodes()), Mat3::Zero());
  std::vector<char> crossed(axes.size(), 0);
  for (const auto& el : model.elements()) {
    const Vec3 e1 = (model.node(el.n2).X - model.node(el.n1).X).normalized();
    for (int n : {el.n1, el.n2}) {
      Mat3& E = axes[n];
      if (E.isZero(0)) {  // the first member: its section's axes
        const Vec3 e3 = e1.cross(el.y_ref).normalized();
        E << e1, e3.cross(e1), e3;
      } else if (!crossed[n] && E.col(0).cross(e1).norm() > 1e-6) {  // the first across it
        const Vec3 e2 = (e1 - e1.dot(E.col(0)) * E.col(0)).normalized();
        E.col(1) = e2;
        E.col(2) = E.col(0).cross(e2);
        crossed[n] = 1;
      }
    }
  }
  // A node inside a straight member takes the axes of a node along it that has a member across
  // (a post's inner nodes: the frame's axes, not the post's section axes, which ignore a yaw).
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& el : model.elements())
      if (crossed[el.n1] != crossed[el.n2]) {
        const int from = crossed[el.n1] ? el.n1 : el.n2, to = crossed[el.n1] ? el.n2 : el.n1;
        axes[to] = axes[from];
        crossed[to] = 1;
        changed = true;
      }
  }
  for (auto& E : axes)
    if (E.isZero(0)) E = Mat3::Identity();
  return axes;
}

// The hull of the corners of a cube around each of `nodes`, of half side half_width[n] (half the width
// of its narrowest member) and axes axes[n] (cube_axes): contact at the members' surfaces. For a rigid
// body's nodes, its outer envelope (a cabinet of 50 mm tubes tips about its outer edges, not 25 mm
// inside and above them); for one node, its cube (a flexible body's node: six faces of four corners,
// each corner a quarter of the node). Only the hull's vertices are appended to `points`; the geometry
// names them by their index there.
inline SupportGeometry surface_support_geometry(const Model& model, const std::vector<int>& nodes,
                                                const std::vector<double>& half_width, const std::vector<Mat3>& axes,
                                                std::vector<SurfacePoint>& points) {
  // The corners are numbered from 0 here (the hull's canonical order depends only on their relative
  // order), then as their place in `points`.
  support::Points P;
  std::vector<int> owner, ids;
  std::vector<SurfacePoint> corners;
  for (int n : nodes) {
    const double c = std::isfinite(half_width[n]) ? half_width[n] : 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 s((corner & 1) ? 1.0 : -1.0, (corner & 2) ? 1.0 : -1.0, (corner & 4) ? 1.0 : -1.0);
      const Vec3 arm = c * (axes[n] * s);
      ids.push_back(static_cast<int>(P.size()));
      P.push_back(model.node(n).X + arm);
      owner.push_back(n);
      corners.push_back({n, arm});
    }
  }
  SupportGeometry g = hull_geometry(P, ids, owner);
  // Only the hull's vertices are contact points: keep those, renumbered in order.
  std::vector<int> renumber(P.size(), -1);
  for (int i : g.vertices) renumber[i] = static_cast<int>(points.size()), points.push_back(corners[i]);
  for (int& i : g.vertices) i = renumber[i];
  for (auto& f : g.faces) {
    for (int& i : f.vertices) i = renumber[i];
    for (int& i : f.frame) i = renumber[i];
  }
  return g;
}

}  // namespace furniture_fem::detail
