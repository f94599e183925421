#pragma once
// furniture_fem/contact/cgal_adapter.hpp: everything of the contact module that needs CGAL. This header
// declares it without CGAL; what calls CGAL is defined in detail/cgal_adapter_impl.hpp, included at the
// end here (header-only use) or compiled once in furniture_fem::contact_compiled, whose users get
// FURNITURE_FEM_COMPILED_CONTACT and never parse CGAL (docs/performance.md section 6).
//
//  - ElementBox, BroadPhase: candidate element pairs from inflated axis-aligned boxes, body boxes
//    first, then CGAL::box_intersection_d between two bodies' element boxes (or
//    box_self_intersection_d within a body when asked), output sorted (i < j) so results do not
//    depend on CGAL's traversal order;
//  - TriangleMesh, read_triangle_mesh(): OFF, OBJ, STL (ASCII and binary) readers that name the file
//    and line of what is wrong (InputError);
//  - MeshObstacle: a rigid triangle mesh in a CGAL AABB tree: closest point to a point, and the
//    segments (beam elements) within a distance of the mesh;
//  - detail::convex_hull_triangles: a point set's convex hull (a rigid body's support points).
// CGAL version differences (AABB_traits in 5.x, AABB_traits_3 from 6.0) are kept in the definitions.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../core/model.hpp"
#include "contact_geometry.hpp"
#include "../core/errors.hpp"
#include "../core/text.hpp"

// FFEM_CONTACT_DETECTION_INLINE: how the definitions in detail/cgal_adapter_impl.hpp (and the convex hull
// of detail/support_points.hpp) are declared: inline when included by users (header-only), and with
// external linkage in the one unit that compiles them (FURNITURE_FEM_BUILDING_CONTACT_LIBRARY).
#ifdef FURNITURE_FEM_BUILDING_CONTACT_LIBRARY
#define FFEM_CONTACT_DETECTION_INLINE
#else
#define FFEM_CONTACT_DETECTION_INLINE inline
#endif

namespace furniture_fem {

// ---------------------------------------------------------------------------------------------
// Broad phase.

// The axis-aligned box of one element: its segment inflated by the element's radius (half its
// contact width) plus a margin that covers the motion until the next broad-phase update.
struct ElementBox {
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  int element = -1;              // the id reported in pairs (usually the model's element index)
  int body = 0;                  // items are bodies; pairs inside one body are skipped by default
  int node_a = -1, node_b = -1;  // optional: elements sharing a node are never paired (self-contact)

  static ElementBox around(const Vec3& p_W0, const Vec3& p_W1, double inflate, int element, int body,
                           int node_a = -1, int node_b = -1) {
    ElementBox b;
    const Vec3 r = Vec3::Constant(inflate);
    b.lo = p_W0.cwiseMin(p_W1) - r;
    b.hi = p_W0.cwiseMax(p_W1) + r;
    b.element = element;
    b.body = body;
    b.node_a = node_a;
    b.node_b = node_b;
    return b;
  }
  // Closed boxes: touching counts, as in CGAL's default (CLOSED) topology.
  bool overlaps(const ElementBox& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
  bool shares_node(const ElementBox& o) const {
    return (node_a >= 0 && (node_a == o.node_a || node_a == o.node_b)) ||
           (node_b >= 0 && (node_b == o.node_a || node_b == o.node_b));
  }
};

// Candidate element pairs for the narrow phase. Bodies' boxes (the union of their element boxes)
// are tested first; only for two bodies whose boxes overlap are element boxes tested, and only the
// elements that reach into the other body's box, by CGAL::box_intersection_d (bipartite). Pairs
// within one body are produced only when same_body_pairs is set (self-contact of a folding item),
// by CGAL::box_self_intersection_d, skipping elements that share a node (they always touch).
// The result lists each pair once as (smaller id, larger id), sorted, so it does not depend on the
// order of the input or on CGAL's traversal. Ids must be unique; body ids must be non-negative.
class BroadPhase {
 public:
  bool same_body_pairs = false;
  std::ptrdiff_t cutoff = 10;  // CGAL's segment-tree cutoff: below it, boxes are scanned directly

  std::vector<std::pair<int, int>> pairs(std::span<const ElementBox> boxes) {
    std::vector<std::pair<int, int>> out;
    pairs(boxes, out);
    return out;
  }

  // The same, into a caller's vector (cleared first). The broad phase's own buffers (body boxes, the
  // two sides' indices, the pair keys) are reused from call to call; CGAL's copies of a body pair's
  // boxes are made per call (CGAL reorders them, and they cannot be members without CGAL here), once
  // per re-run of the broad phase, not per step.
  void pairs(std::span<const ElementBox> boxes, std::vector<std::pair<int, int>>& out);

  // Body pairs whose boxes overlapped in the last call (for statistics and tests).
  int body_pairs_tested() const { return body_pairs_tested_; }

 private:
  // The sign bit is flipped so that unsigned order of the key is the signed order of the ids.
  static std::uint64_t pack(int id) { return static_cast<std::uint32_t>(id) ^ 0x80000000u; }
  static int unpack(std::uint64_t key) { return static_cast<int>(static_cast<std::uint32_t>(key) ^ 0x80000000u); }
  void add(int i, int j) { keys_.push_back(pack(std::min(i, j)) << 32 | pack(std::max(i, j))); }

  void group_by_body(std::span<const ElementBox> boxes) {
    body_ids_.clear();
    for (const auto& b : boxes) {
      if (b.body < 0)
        throw ModelError("BroadPhase: element " + std::to_string(b.element) + " has a negative body id (" +
                         std::to_string(b.body) + ")");
      body_ids_.push_back(b.body);
    }
    std::sort(body_ids_.begin(), body_ids_.end());
    body_ids_.erase(std::unique(body_ids_.begin(), body_ids_.end()), body_ids_.end());
    const std::size_t nb = body_ids_.size();
    members_.resize(nb);
    for (auto& m : members_) m.clear();
    ElementBox empty;
    empty.lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    empty.hi = -empty.lo;
    body_box_.assign(nb, empty);
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const std::size_t k = static_cast<std::size_t>(
          std::lower_bound(body_ids_.begin(), body_ids_.end(), boxes[i].body) - body_ids_.begin());
      members_[k].push_back(i);
      body_box_[k].lo = body_box_[k].lo.cwiseMin(boxes[i].lo);
      body_box_[k].hi = body_box_[k].hi.cwiseMax(boxes[i].hi);
    }
  }

  // The boxes of `body` that reach into `region` (their indices in `boxes`).
  void collect(std::span<const ElementBox> boxes, std::size_t body, const ElementBox& region,
               std::vector<std::size_t>& set) const {
    set.clear();
    for (std::size_t i : members_[body])
      if (boxes[i].overlaps(region)) set.push_back(i);
  }

  std::vector<int> body_ids_;
  std::vector<std::vector<std::size_t>> members_;
  std::vector<ElementBox> body_box_;
  std::vector<std::size_t> set_a_, set_b_;  // the two sides' boxes (indices) of a body pair
  std::vector<std::uint64_t> keys_;
  int body_pairs_tested_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Convex hull.

namespace detail {
// The triangles of the convex hull of the points P[i], i in `points` (CGAL::convex_hull_3), each as three
// indices into P in CGAL's order; none for fewer than four points or a flat set (fewer than four
// faces). CGAL's listing depends on the points' order and on the heap: callers put it in a canonical
// form (detail/support_points.hpp).
std::vector<std::array<int, 3>> convex_hull_triangles(const std::vector<Vec3>& P, const std::vector<int>& points);
}  // namespace detail

// ---------------------------------------------------------------------------------------------
// Triangle meshes from files.

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;  // indices into vertices
};

namespace detail {

// The mesh readers use the core text helpers (core/text.hpp): numbered lines, comments stripped,
// words, strict numbers (coordinates must be finite).
using text::lowercase;
using text::parse_finite;
using text::parse_integer;
using text::split_lines;
using text::split_words;
using text::strip_comment;

inline Vec3 parse_point(const std::string& file, long line, const std::string& field,
                        const std::vector<std::string_view>& w, std::size_t first) {
  Vec3 p;
  for (int k = 0; k < 3; ++k)
    if (first + k >= w.size() || !parse_finite(w[first + k], p[k]))
      throw InputError(file, line, field,
                       "expected three finite coordinates" +
                           (first + k < w.size() ? ", got '" + std::string(w[first + k]) + "'" : std::string(", line too short")));
  return p;
}

// Fan triangulation of a polygon face (exact for the convex faces mesh files hold).
inline void add_polygon(TriangleMesh& mesh, const std::vector<int>& face) {
  for (std::size_t k = 1; k + 1 < face.size(); ++k) mesh.triangles.push_back({face[0], face[k], face[k + 1]});
}

inline TriangleMesh read_off(const std::string& file, const std::string& text) {
  const text::Lines t = split_lines(file, text);
  std::size_t i = 0;
  auto next_line = [&](const char* what) -> std::pair<long, std::string> {
    while (i < t.lines.size()) {
      std::string s = strip_comment(t.lines[i]);
      ++i;
      if (!s.empty()) return {static_cast<long>(i), s};
    }
    throw InputError(file, static_cast<long>(t.lines.size()), what, "the file ends early");
  };
  auto [hline, header] = next_line("header");
  auto hw = split_words(header);
  const std::string magic(hw[0]);
  if (magic.size() < 3 || magic.substr(magic.size() - 3) != "OFF" || magic.find("4") != std::string::npos ||
      magic.find("n") != std::string::npos)
    throw InputError(file, hline, "header", "expected 'OFF' (or COFF/NOFF/CNOFF), got '" + magic + "'");
  std::vector<std::string_view> counts(hw.begin() + 1, hw.end());
  long count_line = hline;
  std::string count_text;
  if (counts.empty()) {
    auto [cl, ct] = next_line("counts");
    count_line = cl;
    count_text = std::move(ct);
    counts = split_words(count_text);
  }
  long nv = 0, nf = 0;
  if (counts.size() < 2 || !parse_integer(counts[0], nv) || !parse_integer(counts[1], nf) || nv < 0 || nf < 0)
    throw InputError(file, count_line, "counts", "expected 'vertices faces edges' as non-negative integers");
  if (nv == 0 || nf == 0) throw InputError(file, count_line, "counts", "the mesh is empty (no vertices or no faces)");
  TriangleMesh mesh;
  // Each vertex takes a line: reserve no more than the file has left (a claimed count of 1e12 gave a
  // length_error; now the file ends early at the first vertex it lacks).
  mesh.vertices.reserve(static_cast<std::size_t>(std::min<long>(nv, static_cast<long>(t.lines.size() - i))));
  for (long v = 0; v < nv; ++v) {
    auto [ln, s] = next_line(("vertex " + std::to_string(v)).c_str());
    mesh.vertices.push_back(parse_point(file, ln, "vertex " + std::to_string(v), split_words(s), 0));
  }
  std::vector<int> face;
  for (long f = 0; f < nf; ++f) {
    const std::string field = "face " + std::to_string(f);
    auto [ln, s] = next_line(field.c_str());
    const auto w = split_words(s);
    long n = 0;
    if (!parse_integer(w[0], n) || n < 3)
      throw InputError(file, ln, field, "expected a vertex count of at least 3, got '" + std::string(w[0]) + "'");
    if (n > static_cast<long>(w.size()) - 1)  // not n + 1 > size: n may be LONG_MAX
      throw InputError(file, ln, field, "declares " + std::to_string(n) + " vertices but lists " + std::to_string(w.size() - 1));
    face.clear();
    for (long k = 1; k <= n; ++k) {
      long idx = 0;
      if (!parse_integer(w[k], idx) || idx < 0 || idx >= nv)
        throw InputError(file, ln, field, "vertex index '" + std::string(w[k]) + "' is not in [0, " + std::to_string(nv) + ")");
      face.push_back(static_cast<int>(idx));
    }
    add_polygon(mesh, face);
  }
  return mesh;
}

inline TriangleMesh read_obj(const std::string& file, const std::string& text) {
  const text::Lines t = split_lines(file, text);
  TriangleMesh mesh;
  struct PendingFace {
    long line;
    std::vector<long> indices;
  };
  std::vector<PendingFace> faces;
  for (std::size_t i = 0; i < t.lines.size(); ++i) {
    const long ln = static_cast<long>(i + 1);
    const std::string s = strip_comment(t.lines[i]);
    if (s.empty()) continue;
    const auto w = split_words(s);
    if (w[0] == "v") {
      mesh.vertices.push_back(parse_point(file, ln, "vertex " + std::to_string(mesh.vertices.size() + 1), w, 1));
    } else if (w[0] == "f") {
      if (w.size() < 4) throw InputError(file, ln, "face", "a face needs at least 3 vertices");
      PendingFace f{ln, {}};
      for (std::size_t k = 1; k < w.size(); ++k) {
        const std::string_view tok = w[k].substr(0, w[k].find('/'));  // "v", "v/vt", "v//vn", "v/vt/vn"
        long idx = 0;
        if (!parse_integer(tok, idx) || idx == 0)
          throw InputError(file, ln, "face", "bad vertex reference '" + std::string(w[k]) + "'");
        // Negative indices count back from the vertices read so far.
        f.indices.push_back(idx < 0 ? static_cast<long>(mesh.vertices.size()) + idx : idx - 1);
      }
      faces.push_back(std::move(f));
    }
    // Other statements (vt, vn, o, g, s, usemtl, mtllib, l, ...) carry nothing for contact.
  }
  if (mesh.vertices.empty() || faces.empty())
    throw InputError(file, static_cast<long>(t.lines.size()), "", "the mesh is empty (no 'v' or no 'f' lines)");
  std::vector<int> face;
  for (const auto& f : faces) {
    face.clear();
    for (long idx : f.indices) {
      if (idx < 0 || idx >= static_cast<long>(mesh.vertices.size()))
        throw InputError(file, f.line, "face", "vertex " + std::to_string(idx + 1) + " does not exist (" +
                                                   std::to_string(mesh.vertices.size()) + " vertices)");
      face.push_back(static_cast<int>(idx));
    }
    add_polygon(mesh, face);
  }
  return mesh;
}

inline TriangleMesh read_stl_ascii(const std::string& file, const std::string& text) {
  const text::Lines t = split_lines(file, text);
  TriangleMesh mesh;
  enum class Where { before_solid, in_solid, in_facet, in_loop, after_loop, done } where = Where::before_solid;
  long facet_line = 0;
  int loop_vertices = 0;
  for (std::size_t i = 0; i < t.lines.size() && where != Where::done; ++i) {
    const long ln = static_cast<long>(i + 1);
    const std::string s = strip_comment(t.lines[i], '\0');
    if (s.empty()) continue;
    const auto w = split_words(s);
    const std::string key = lowercase(std::string(w[0]));
    const std::string field = "facet " + std::to_string(mesh.triangles.size());
    auto expect = [&](bool ok, const std::string& what) {
      if (!ok) throw InputError(file, ln, field, "expected " + what + ", got '" + s + "'");
    };
    switch (where) {
      case Where::before_solid:
        expect(key == "solid", "'solid'");
        where = Where::in_solid;
        break;
      case Where::in_solid:
        if (key == "endsolid") {
          where = Where::done;
          break;
        }
        expect(key == "facet", "'facet normal' or 'endsolid'");
        facet_line = ln;
        where = Where::in_facet;
        break;
      case Where::in_facet:
        expect(key == "outer", "'outer loop'");
        loop_vertices = 0;
        where = Where::in_loop;
        break;
      case Where::in_loop:
        if (key == "endloop") {
          if (loop_vertices != 3)
            throw InputError(file, ln, field, "a facet needs exactly 3 vertices, got " + std::to_string(loop_vertices));
          const int n = static_cast<int>(mesh.vertices.size());
          mesh.triangles.push_back({n - 3, n - 2, n - 1});
          where = Where::after_loop;
          break;
        }
        expect(key == "vertex", "'vertex x y z' or 'endloop'");
        if (++loop_vertices > 3) throw InputError(file, ln, field, "a facet needs exactly 3 vertices, got more");
        mesh.vertices.push_back(parse_point(file, ln, field, w, 1));
        break;
      case Where::after_loop:
        expect(key == "endfacet", "'endfacet'");
        where = Where::in_solid;
        break;
      case Where::done:
        break;
    }
  }
  if (where != Where::done)
    throw InputError(file, static_cast<long>(t.lines.size()),
                     where == Where::in_solid ? "endsolid" : "facet " + std::to_string(mesh.triangles.size()),
                     where == Where::in_solid ? std::string("the file ends without 'endsolid'")
                                              : "the file ends inside the facet opened on line " + std::to_string(facet_line));
  if (mesh.triangles.empty()) throw InputError(file, static_cast<long>(t.lines.size()), "", "the mesh is empty (no facets)");
  return mesh;
}

// Binary STL: 80-byte header, uint32 count, then 50 bytes per triangle (normal, 3 vertices as
// little-endian float32, 2 attribute bytes). Errors name the triangle and byte offset (no lines).
inline TriangleMesh read_stl_binary(const std::string& file, const std::string& bytes) {
  static_assert(std::endian::native == std::endian::little, "furniture_fem: the binary STL reader assumes a little-endian host");
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  if (count == 0) throw InputError(file, 0, "triangle count", "the mesh is empty (binary STL with 0 triangles)");
  const std::size_t need = 84 + 50 * static_cast<std::size_t>(count);
  if (bytes.size() != need)
    throw InputError(file, 0, "triangle count",
                     "binary STL declares " + std::to_string(count) + " triangles (" + std::to_string(need) +
                         " bytes) but the file has " + std::to_string(bytes.size()) + " bytes");
  TriangleMesh mesh;
  mesh.vertices.reserve(3 * static_cast<std::size_t>(count));
  mesh.triangles.reserve(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::size_t at = 84 + 50 * static_cast<std::size_t>(k);
    float xyz[9];
    std::memcpy(xyz, bytes.data() + at + 12, sizeof xyz);
    for (int c = 0; c < 9; ++c)
      if (!std::isfinite(xyz[c]))
        throw InputError(file, 0, "triangle " + std::to_string(k),
                         "coordinate is not finite (byte " + std::to_string(at + 12 + 4 * c) + ")");
    const int n = static_cast<int>(mesh.vertices.size());
    for (int v = 0; v < 3; ++v) mesh.vertices.emplace_back(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    mesh.triangles.push_back({n, n + 1, n + 2});
  }
  return mesh;
}

inline TriangleMesh read_stl(const std::string& file, const std::string& bytes) {
  // A binary file may also start with "solid"; its size settles it.
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<std::size_t>(count)) return read_stl_binary(file, bytes);
  }
  // Text that starts with "solid" is ASCII; NUL bytes mark a (broken) binary file that happens to
  // start with "solid", whose size mismatch is then the error to report.
  const auto b = bytes.find_first_not_of(" \t\r\n");
  const bool text = bytes.find('\0') == std::string::npos;
  if (text && b != std::string::npos && lowercase(bytes.substr(b, 5)) == "solid") return read_stl_ascii(file, bytes);
  if (bytes.size() < 84)
    throw InputError(file, 1, "", "neither ASCII STL (no 'solid') nor binary STL (shorter than the 84-byte header)");
  return read_stl_binary(file, bytes);  // reports the size mismatch
}

}  // namespace detail

// Reads a triangle mesh by its extension: .off, .obj, .stl (ASCII or binary). Polygons are fan-
// triangulated. Throws InputError naming the file, the line (0 for binary data) and the field for
// a missing or empty file, a malformed line, a bad index or a truncated file.
inline TriangleMesh read_triangle_mesh(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the mesh file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (bytes.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError(path, 1, "", "the mesh file is empty");
  const auto dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : detail::lowercase(path.substr(dot + 1));
  if (ext == "off") return detail::read_off(path, bytes);
  if (ext == "obj") return detail::read_obj(path, bytes);
  if (ext == "stl") return detail::read_stl(path, bytes);
  throw InputError(path, 0, "", "unknown mesh format '." + ext + "' (expected .off, .obj or .stl)");
}

// ---------------------------------------------------------------------------------------------
// Rigid triangle-mesh obstacle.

namespace detail {
inline std::string coordinate_text(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

struct CgalMeshTree;  // the AABB tree and its triangles (detail/cgal_adapter_impl.hpp)
}  // namespace detail

struct MeshClosestPoint {
  Vec3 p_WM = Vec3::Zero();      // closest point on the mesh
  double distance = 0;
  int triangle = -1;             // index in mesh().triangles
  Vec3 n_W = Vec3::Zero();       // that triangle's unit normal (right-hand rule on its vertex order)
};

// One element's segment to be tested against a mesh.
struct MeshQuerySegment {
  Vec3 p_W0 = Vec3::Zero(), p_W1 = Vec3::Zero();
};

struct SegmentMeshContact {
  int segment = -1;   // index in the query list
  int triangle = -1;  // index in mesh().triangles of the closest triangle
  SegmentTriangleClosest closest;
};

// A rigid obstacle given as a triangle mesh, in the world (table) frame, held in a CGAL AABB tree.
// Triangles of zero area are dropped (CGAL's distance queries do not accept them); a mesh with none
// left is an error. Copies share the immutable tree.
class MeshObstacle {
 public:
  // Vertices must lie within this distance of the origin on each axis (m). Far beyond, CGAL's squared
  // distances and areas overflow: a vertex at 1e166 m passed the zero-area test with an infinite
  // area, and the first distance query threw a CGAL precondition failure (found by fuzzing,
  // docs/fuzzing.md). Scenes bound obstacles tighter (10 km of the table's centre).
  static constexpr double max_coordinate = 1e6;

  explicit MeshObstacle(TriangleMesh mesh, std::string name = "mesh");

  static MeshObstacle from_file(const std::string& path) { return MeshObstacle(read_triangle_mesh(path), path); }

  // The point of the mesh nearest to Q.
  Vec3 closest_point(const Vec3& p_WQ) const { return closest(p_WQ).p_WM; }

  MeshClosestPoint closest(const Vec3& p_WQ) const;

  // The point of the mesh nearest to Q if one lies within distance d of Q; nothing otherwise. Cheap for
  // a point far from the mesh: the box of half-width d around Q is tested against the mesh's box, then
  // against the tree's triangles (a triangle within d of Q meets that box), before any closest-point
  // search (whose cost grows with the distance: a far query visits most of the tree).
  std::optional<MeshClosestPoint> closest_within(const Vec3& p_WQ, double d) const;

  // The segments within distance d of the mesh (a capsule of radius d touches it), each with its
  // closest triangle and closest points: one contact per segment, as the paper has one per element
  // pair. Candidates come from the tree (triangles whose boxes meet the segment's box inflated by
  // d); the exact distance is closest_points_segment_triangle. Output in segment order.
  std::vector<SegmentMeshContact> segments_within(std::span<const MeshQuerySegment> segments, double d) const {
    std::vector<SegmentMeshContact> out;
    segments_within(segments, d, out);
    return out;
  }
  void segments_within(std::span<const MeshQuerySegment> segments, double d, std::vector<SegmentMeshContact>& out) const;

  const TriangleMesh& mesh() const { return mesh_; }
  const std::string& name() const { return name_; }
  std::size_t num_triangles() const;

 private:
  std::string name_;
  TriangleMesh mesh_;
  std::shared_ptr<const detail::CgalMeshTree> tree_;
};

}  // namespace furniture_fem

// The definitions that call CGAL: here when used header-only; the compiled contact library's users
// (FURNITURE_FEM_COMPILED_CONTACT) link them instead.
#if !defined(FURNITURE_FEM_COMPILED_CONTACT) || defined(FURNITURE_FEM_BUILDING_CONTACT_LIBRARY)
#ifdef FURNITURE_FEM_CONTACT_INTERNAL  // included from the module's own internals: leave it defined
#include "detail/cgal_adapter_impl.hpp"
#else
#define FURNITURE_FEM_CONTACT_INTERNAL
#include "detail/cgal_adapter_impl.hpp"
#undef FURNITURE_FEM_CONTACT_INTERNAL
#endif
#endif
