#pragma once
// furniture_fem/furniture/furniture.hpp: parametric builders for the paper's five furniture items and for new
// ones, each built as one body (two for the separated cabinets) of beam grids into a Model.
//
// Item frame: x along the width W (the longer edge), y along the depth D with the front at y = -D/2,
// z up from the item's base; the footprint centre is the origin. A Placement puts the item on the
// table: x_world = Rz(yaw) x_local + (x, y, z). Panels (sides, back, doors, shelves, boards) are grids
// of beams, as in the paper. Member centre lines sit half a member width inside the outer envelope, so
// the outer dimensions are those of Table 2 and the bottom nodes sit exactly at floor contact onset
// (the floor contact distance is half the member width). Each body's mass and centre of gravity are
// matched to Table 2 by scaling member densities (detail/furniture_calibration.hpp).
// See docs/furniture/furniture.md for drawings, counts and the choices made where the paper is silent.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "../core/model.hpp"
#include "item_kind.hpp"

#define FURNITURE_FEM_FURNITURE_INTERNAL
#include "detail/furniture_calibration.hpp"
#include "detail/furniture_wireframe.hpp"
#undef FURNITURE_FEM_FURNITURE_INTERNAL

namespace furniture_fem {

inline constexpr double newtons_per_kgf = 9.80665;
// Friction between items (0.8 x the static value measured between the separated cabinets).
inline constexpr double mu_between_furniture = 0.169;

// ---------------------------------------------------------------------------------------------------
// Kinds and the paper's data
// ---------------------------------------------------------------------------------------------------

// How finely an item is meshed. full: the paper's 50 mm elements and tuned panel grids; coarse: grid
// and element length doubled; rigid: the coarse mesh, flagged for a simulation that treats the body
// as rigid; automatic ("auto" in scene files): the full mesh, flagged so a runner may choose.
enum class Fidelity { full, coarse, rigid, automatic };

inline std::string to_string(Fidelity f) {
  switch (f) {
    case Fidelity::full: return "full";
    case Fidelity::coarse: return "coarse";
    case Fidelity::rigid: return "rigid";
    case Fidelity::automatic: return "auto";
  }
  return "unknown";
}
inline std::optional<Fidelity> fidelity_from_string(std::string_view s) {
  if (s == "full") return Fidelity::full;
  if (s == "coarse") return Fidelity::coarse;
  if (s == "rigid") return Fidelity::rigid;
  if (s == "auto") return Fidelity::automatic;
  return std::nullopt;
}

// One row of Tables 2 and 4 (lengths in m, masses in kg, alpha and Dc in kgf as printed).
enum class PaperItem { tall_cabinet, upper_separated_cabinet, lower_separated_cabinet, side_table, desk, office_chair };

struct PaperItemData {
  std::string_view name;
  double W, D, H;                            // Table 2 size
  double mass;                               // Table 2 weight (kg)
  double h, d1, d2;                          // centre of gravity: height, from the front, from the back
  double mu_static_long, mu_static_short;    // Table 2 static friction on the floor
  double alpha_kgf, dc_kgf;                  // Table 4
  double mu_long, mu_short, mu_wall;         // Table 4 dynamic friction (as printed)
};

inline const PaperItemData& paper_item(PaperItem item) {
  static constexpr std::array<PaperItemData, 6> rows{{
      {"tall cabinet", 0.900, 0.400, 1.850, 43.6, 0.925, 0.178, 0.222, 0.348, 0.260, 43.6, 52.3, 0.278, 0.208, 0.278},
      {"upper separated cabinet", 0.900, 0.400, 0.730, 21.3, 0.3655, 0.171, 0.229, 0.211, 0.211, 21.3, 25.6, 0.169,
       0.169, 0.169},
      {"lower separated cabinet", 0.900, 0.400, 1.120, 28.8, 0.562, 0.179, 0.221, 0.336, 0.289, 28.8, 34.6, 0.230,
       0.270, 0.270},
      {"side table", 0.550, 0.340, 0.617, 8.0, 0.308, 0.218, 0.122, 0.180, 0.117, 8.0, 9.6, 0.094, 0.144, 0.144},
      {"desk", 1.200, 0.700, 0.700, 30.5, 0.600, 0.380, 0.320, 0.471, 0.443, 30.5, 36.6, 0.377, 0.354, 0.377},
      {"office chair", 0.520, 0.520, 0.810, 6.2, 0.423, 0.260, 0.260, 0.081, 0.048, 6.2, 7.4, 0.065, 0.038, 0.065},
  }};
  return rows[static_cast<size_t>(item)];
}

// ---------------------------------------------------------------------------------------------------
// Contact parameters of an item (SI units)
// ---------------------------------------------------------------------------------------------------

// The paper's contact law (the paper's eqs. 1-4, docs/contact/contact.md) needs, per item: the penalty coefficient alpha,
// the damping coefficient Dc (both forces, N), the penalty index q, and dynamic friction against the
// floor along the item's longer and shorter edges, against the walls and against other items.
struct ItemContact {
  double alpha = 0;            // N (Table 4 gives kgf)
  double Dc = 0;               // N
  double q = 1;
  double mu_floor_long = 0;    // sliding along the longer edge
  double mu_floor_short = 0;   // sliding along the shorter edge
  double mu_wall = 0;
  double mu_item = mu_between_furniture;
  int long_axis = 0;           // item-frame axis of the longer edge: 0 = x (W >= D), 1 = y
  bool casters = false;        // the item rolls on casters (its floor mu are caster values)
  // Its builder placed the nodes so that their contact distance reaches the solid's faces (the block):
  // floor and walls touch its nodes whatever the scene's plane_contact_at.
  bool at_nodes = false;

  // Table 4 as printed (two rows swap Table 2's long/short values; see paper/README.md).
  static ItemContact paper(PaperItem item) {
    const auto& r = paper_item(item);
    ItemContact c;
    c.alpha = r.alpha_kgf * newtons_per_kgf;
    c.Dc = r.dc_kgf * newtons_per_kgf;
    c.mu_floor_long = r.mu_long;
    c.mu_floor_short = r.mu_short;
    c.mu_wall = r.mu_wall;
    c.casters = item == PaperItem::side_table || item == PaperItem::office_chair;
    return c;
  }
  // The paper's rules for new furniture: alpha = weight, q = 1, Dc = 1.2 alpha, mu = 0.8 x static mu,
  // mu against walls = mu along the longer edge, mu between items 0.169.
  static ItemContact from_rule(double mass_kg, double mu_static_long, double mu_static_short, int long_axis = 0) {
    ItemContact c;
    c.alpha = mass_kg * newtons_per_kgf;
    c.Dc = 1.2 * c.alpha;
    c.mu_floor_long = 0.8 * mu_static_long;
    c.mu_floor_short = 0.8 * mu_static_short;
    c.mu_wall = c.mu_floor_long;
    c.long_axis = long_axis;
    return c;
  }
};

// ---------------------------------------------------------------------------------------------------
// Placement, build options and what a builder returns
// ---------------------------------------------------------------------------------------------------

// Where an item stands: footprint centre (x, y) on the table, base elevation z (0 on the floor), yaw
// about z in radians (counter-clockwise seen from above).
struct Placement {
  double x = 0, y = 0, yaw = 0, z = 0;
  static Placement at(double x, double y, double yaw_deg = 0, double z = 0) {
    return {x, y, yaw_deg * std::numbers::pi / 180.0, z};
  }
  Mat3 rotation() const { return Eigen::AngleAxisd(yaw, Vec3::UnitZ()).toRotationMatrix(); }
  Vec3 position() const { return {x, y, z}; }
};

struct BuildOptions {
  std::string name;                       // the body's name; empty: the kind's name
  Fidelity fidelity = Fidelity::full;
  double grid_scale = 1.0;                // multiplies the panel grid spacing (0.5 finer, 2 coarser)
  double element_length = 0.05;           // target element length (the paper's 50 mm)
  std::optional<double> panel_spacing;    // m; replaces the item's tuned panel grid spacing
  // Mass and centre of gravity (h from the base, d1 from the front). Paper items: Table 2 by default.
  // Generic items: an estimate from the panel areas and the geometric centre by default.
  std::optional<double> mass_kg, cog_h, cog_d1;
  // Static friction for the 0.8 rule of generic items (defaults: tall cabinet or desk on carpet).
  std::optional<double> mu_static_long, mu_static_short;
  // Multiplies the members' Young's modulus (and so their shear modulus): the frame's stiffness, for
  // sensitivity studies and for checking a flexible item against its rigid limit. Nothing else changes.
  double stiffness_scale = 1.0;

  // The material of the item's members: steel, its moduli times stiffness_scale.
  Material member_material() const {
    Material m = Material::steel();
    m.E *= stiffness_scale;
    return m;
  }

  double effective_grid_scale() const { return grid_scale * (coarse_mesh() ? 2.0 : 1.0); }
  double effective_element_length() const { return element_length * (coarse_mesh() ? 2.0 : 1.0); }
  bool coarse_mesh() const { return fidelity == Fidelity::coarse || fidelity == Fidelity::rigid; }
};

// An evaluation point for displacement output: the node of `body` nearest to a named point given in
// the item frame.
struct Marker {
  std::string name;
  int body = -1;
  int node = -1;
  Vec3 local_point = Vec3::Zero();
};

struct ItemInfo {
  std::string name;                 // the body's name (separated cabinets: "<item>/upper", "<item>/lower")
  ItemKind kind = ItemKind::tall_cabinet;
  int body = -1;
  std::vector<int> caster_nodes;    // wheel contact points (low friction, Table 4's caster values)
  std::vector<int> bottom_nodes;    // lowest nodes: at contact onset with what the item stands on
  std::vector<Marker> markers;
  // Two nodes on a straight line along the longer edge (contact.long_axis): their current positions
  // give the direction of anisotropic floor friction while the item moves.
  std::array<int, 2> long_axis_nodes{-1, -1};
  ItemContact contact;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // placement rotation (item frame -> world)
  Vec3 position = Vec3::Zero();     // footprint centre at the base, world
  Vec3 size = Vec3::Zero();         // W, D, H (outer)
  Fidelity fidelity = Fidelity::full;
  MassCalibration calibration;

  Vec3 to_local(const Vec3& world) const { return R.transpose() * (world - position); }
  Vec3 to_world(const Vec3& local) const { return R * local + position; }
  const Marker* marker(std::string_view marker_name) const {
    for (const auto& m : markers)
      if (m.name == marker_name) return &m;
    return nullptr;
  }
};

// The member of `body` called `member_name` (as named by the builders, e.g. "top/x0:6"), or -1.
inline int find_member(const Model& model, int body, std::string_view member_name) {
  for (int m : model.body(body).members)
    if (model.member(m).name == member_name) return m;
  return -1;
}

// The node of `body` nearest to a world point.
inline int nearest_node(const Model& model, int body, const Vec3& world_point) {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int n : model.body(body).nodes) {
    const double d = (model.node(n).X - world_point).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = n;
    }
  }
  return best;
}

// The element of `body` whose mid point is nearest to a point given in the item frame, returned as
// (member name, element index within the member): the form scene files use for sectional forces.
inline std::pair<std::string, int> element_near(const Model& model, const ItemInfo& item, const Vec3& local_point) {
  const Vec3 target = item.to_world(local_point);
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (int e : model.body(item.body).elements) {
    const auto& el = model.elements()[e];
    const double d = (0.5 * (model.node(el.n1).X + model.node(el.n2).X) - target).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = e;
    }
  }
  if (best < 0) throw ModelError("element_near: item '" + item.name + "' has no elements");
  const auto& member = model.member(model.elements()[best].member);
  return {member.name, best - member.first_element};
}

// ---------------------------------------------------------------------------------------------------
// Sections (Table 1)
// ---------------------------------------------------------------------------------------------------

namespace sections {
// All members of the cabinets and the desk: 50 x 30 x 2 mm (A = 304 mm^2, Ix = 1.016e5 mm^4).
inline Section cabinet_tube() { return Section::hollow_rectangle(0.050, 0.030, 0.002, "50x30x2 tube (Table 1)"); }
inline Section side_table_front_column() {
  return Section::hollow_rectangle(0.170, 0.040, 0.002, "side table front column 170x40x2 (Table 1)");
}
// Type 2: Table 1 gives only A, Ix, Iy. Outer size chosen 170 x 80 mm: as deep as the front column
// (the two columns of a side are the front and rear halves of its 340 mm depth).
inline Section side_table_rear_column() {
  return Section::from_properties("side table rear column, type 2 (Table 1)", 1764e-6, 4.867e-6, 1.488e-5, 0.170,
                                  0.080);
}
inline Section side_table_beam() {
  return Section::hollow_rectangle(0.445, 0.040, 0.002, "side table beam 445x40x2 (Table 1)");
}
inline Section chair_backrest() {
  return Section::hollow_rectangle(0.300, 0.080, 0.002, "office chair backrest 300x80x2 (Table 1)");
}
inline Section chair_seat() {
  return Section::hollow_rectangle(0.400, 0.080, 0.002, "office chair seat 400x80x2 (Table 1)");
}
// Type 3: Table 1 gives only A = 704 mm^2 and I = 2.773e5 mm^4 about both axes. A radius of gyration
// of 19.8 mm fits a 50 mm square profile with a 3.5 mm wall: outer size chosen 50 x 50 mm.
inline Section chair_base() {
  return Section::from_properties("office chair base, type 3 (Table 1)", 704e-6, 2.773e-7, 2.773e-7, 0.050, 0.050);
}
// Casters are not in Table 1: a 50 mm steel tube stands for stem and wheel, so the wheel contact
// point sits 25 mm above the floor like every other bottom node of a 50 mm member.
inline Section caster() { return Section::circular_tube(0.050, 0.002, "caster (stem and wheel)"); }
}  // namespace sections

// ---------------------------------------------------------------------------------------------------
// Builders. Each adds one body (two for the separated cabinets) to the model and returns what a
// simulation needs about it. Impossible options throw ModelError naming the item; the model then
// holds a partly built body and should be discarded.
// ---------------------------------------------------------------------------------------------------

namespace detail {

// Panel grid spacings tuned so that the paper's configurations come out near its element and node
// counts (docs/furniture/furniture.md). They are starting values; BuildOptions::panel_spacing replaces them.
inline constexpr double tall_cabinet_spacing = 0.095;
inline constexpr double upper_cabinet_spacing = 0.095;
inline constexpr double lower_cabinet_spacing = 0.095;
inline constexpr double desk_top_spacing = 0.100;
inline constexpr double side_table_spacing = 0.255;
inline constexpr double generic_spacing = 0.100;
// Mass estimate of generic sheet-steel furniture: the paper's cabinets weigh 6.6-7.2 kg per m^2 of
// panel (about 0.9 mm sheet with its stiffeners).
inline constexpr double sheet_areal_mass = 7.0;     // kg/m^2
inline constexpr double table_top_areal_mass = 10.0;  // kg/m^2, a steel top with its apron

// Everything a builder decides before touching the model.
struct Blueprint {
  std::string name;
  ItemKind kind = ItemKind::tall_cabinet;
  Vec3 size = Vec3::Zero();
  Wireframe wire;
  std::vector<std::string> caster_lines;                   // line end a = wheel contact point
  std::vector<std::pair<std::string, Vec3>> marker_points; // item frame
  double mass = 0;
  std::optional<Vec3> cog;                                 // item frame; none: keep the geometric centre
  ItemContact contact;
};

inline void check_options(const BuildOptions& o, const std::string& who) {
  auto positive = [&](double v, const char* what) {
    if (!(v > 0) || !std::isfinite(v))
      throw ModelError(who + ": " + what + " must be positive and finite (got " + fmt(v) + ")");
  };
  positive(o.grid_scale, "grid_scale");
  positive(o.element_length, "element_length");
  if (o.panel_spacing) positive(*o.panel_spacing, "panel_spacing");
  if (o.mass_kg) positive(*o.mass_kg, "mass_kg");
  if (o.cog_h) positive(*o.cog_h, "cog_h");
  if (o.cog_d1) positive(*o.cog_d1, "cog_d1");
  for (auto mu : {o.mu_static_long, o.mu_static_short})
    if (mu && (!(*mu >= 0) || !std::isfinite(*mu)))
      throw ModelError(who + ": static friction must be non-negative (got " + fmt(*mu) + ")");
}

inline void check_size(double W, double D, double H, const std::string& who) {
  // Below 0.15 m a panel has no room for a grid of 50 mm members.
  for (auto [v, what] : {std::pair{W, "W"}, std::pair{D, "D"}, std::pair{H, "H"}})
    if (!(v >= 0.15) || !(v <= 10.0))
      throw ModelError(who + ": " + what + " must lie in [0.15, 10] m (got " + fmt(v) + ")");
}

// Centre-of-gravity target in the item frame from h (above the base) and d1 (from the front).
inline Vec3 cog_target(double D, double h, double d1) { return {0.0, -0.5 * D + d1, h}; }

// A generic item's mass is spread evenly over its members unless cog_h / cog_d1 are given, so its centre
// of gravity is its mesh's. Built coarse or rigid it takes the centre of its full mesh instead: the
// coarser panel grid has fewer top members against the same legs, and a rigid table stood 22 mm lower
// than the full one (3.5 %: it tipped 3 to 5 % later; docs/contact/verification_contact.md). `build`
// builds the item with the options it is given.
template <class Build>
BuildOptions with_full_mesh_cog(const BuildOptions& opts, double D, Build&& build) {
  if (!opts.coarse_mesh() || (opts.cog_h && opts.cog_d1)) return opts;
  BuildOptions full = opts;
  full.fidelity = Fidelity::full;
  Model scratch;
  const ItemInfo item = build(scratch, full);
  const Vec3 c = item.to_local(scratch.body_centre_of_gravity(item.body));
  BuildOptions o = opts;
  if (!o.cog_h) o.cog_h = c.z();
  if (!o.cog_d1) o.cog_d1 = c.y() + 0.5 * D;
  return o;
}

// The two nodes farthest apart along item axis `axis` among nodes that share the other two item
// coordinates: the ends of the longest straight line of nodes in that direction.
inline std::array<int, 2> longest_line_along(const Model& model, const ItemInfo& info, int axis) {
  std::map<std::pair<long long, long long>, std::array<int, 2>> lines;
  std::map<std::pair<long long, long long>, std::array<double, 2>> ends;
  const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
  for (int n : model.body(info.body).nodes) {
    const Vec3 x = info.to_local(model.node(n).X);
    const auto key = std::make_pair(std::llround(x[a1] / 1e-6), std::llround(x[a2] / 1e-6));
    auto [it, fresh] = ends.try_emplace(key, std::array<double, 2>{x[axis], x[axis]});
    if (fresh) lines[key] = {n, n};
    if (x[axis] < it->second[0]) {
      it->second[0] = x[axis];
      lines[key][0] = n;
    }
    if (x[axis] > it->second[1]) {
      it->second[1] = x[axis];
      lines[key][1] = n;
    }
  }
  std::array<int, 2> best{-1, -1};
  double best_span = 0;
  for (const auto& [key, e] : ends)
    if (e[1] - e[0] > best_span + 1e-9) {
      best_span = e[1] - e[0];
      best = lines[key];
    }
  return best;
}

inline ItemInfo realize(Model& model, const Blueprint& bp, const Placement& placement, const BuildOptions& opts) {
  const int material = find_or_add_material(model, opts.member_material());
  ItemInfo info;
  info.name = bp.name;
  info.kind = bp.kind;
  info.body = model.add_body(bp.name);
  info.R = placement.rotation();
  info.position = placement.position();
  info.size = bp.size;
  info.fidelity = opts.fidelity;
  info.contact = bp.contact;
  const RealizedWireframe built =
      bp.wire.realize(model, info.body, material, info.R, info.position, opts.effective_element_length());
  const std::string who = "item '" + bp.name + "'";
  const Vec3 cog_now = info.to_local(model.body_centre_of_gravity(info.body));
  info.calibration = calibrate_mass(model, info.body, info.R, info.position, bp.mass, bp.cog.value_or(cog_now), who);

  for (const auto& line : bp.caster_lines) info.caster_nodes.push_back(built.line_end_a_node.at(line));
  double z_min = std::numeric_limits<double>::infinity();
  for (int n : model.body(info.body).nodes) z_min = std::min(z_min, info.to_local(model.node(n).X).z());
  for (int n : model.body(info.body).nodes)
    if (info.to_local(model.node(n).X).z() <= z_min + wire_tolerance) info.bottom_nodes.push_back(n);
  info.long_axis_nodes = longest_line_along(model, info, bp.contact.long_axis);
  for (const auto& [marker_name, local] : bp.marker_points)
    info.markers.push_back(Marker{marker_name, info.body, nearest_node(model, info.body, info.to_world(local)), local});
  return info;
}

// A cabinet-like box: top, bottom, sides, back, optional closed front (doors) and shelves, all grids
// on one lattice so that every panel edge is shared node for node with its neighbour.
struct Carcass {
  double W = 0, D = 0, H = 0;
  double spacing = 0.1;
  std::vector<double> shelf_fractions;  // shelf heights as fractions of the inner height, snapped to the lattice
  bool closed_front = true;             // doors (a grid) or open shelves (edges only)
  int section = 0;
};

inline std::vector<double> evenly_spaced(int shelves) {
  std::vector<double> f;
  for (int s = 1; s <= shelves; ++s) f.push_back(double(s) / (shelves + 1));
  return f;
}

inline double carcass_panel_area(const Carcass& c) {
  return 2 * c.D * c.H + c.W * c.H + (c.closed_front ? c.W * c.H : 0.0) +
         (2.0 + static_cast<double>(c.shelf_fractions.size())) * c.W * c.D;
}

inline void add_carcass(Wireframe& wire, const Carcass& c, double inset) {
  const double x0 = -0.5 * c.W + inset, x1 = 0.5 * c.W - inset;
  const double y0 = -0.5 * c.D + inset, y1 = 0.5 * c.D - inset;
  const double z0 = inset, z1 = c.H - inset;
  // An even count across the width puts a node on the centre line, where the markers are.
  const auto xs = lattice(x0, x1, c.spacing, 2), ys = lattice(y0, y1, c.spacing), zs = lattice(z0, z1, c.spacing);
  wire.panel("top", 2, z1, xs, ys, c.section);
  wire.panel("bottom", 2, z0, xs, ys, c.section);
  wire.panel("left", 0, x0, ys, zs, c.section);
  wire.panel("right", 0, x1, ys, zs, c.section);
  wire.panel("back", 1, y1, xs, zs, c.section);
  if (c.closed_front) wire.panel("front", 1, y0, xs, zs, c.section);
  std::vector<double> levels;
  for (double f : c.shelf_fractions) {
    const double z = snap_interior(zs, z0 + (z1 - z0) * f);
    if (std::find(levels.begin(), levels.end(), z) == levels.end()) levels.push_back(z);
  }
  for (size_t s = 0; s < levels.size(); ++s)
    wire.panel("shelf" + std::to_string(s + 1), 2, levels[s], xs, ys, c.section);
}

inline void add_cabinet_markers(Blueprint& bp, double W, double D, double H) {
  bp.marker_points = {{"top_front_corner", Vec3(-0.5 * W, -0.5 * D, H)},
                      {"top_front_centre", Vec3(0, -0.5 * D, H)},
                      {"top_centre", Vec3(0, 0, H)}};
}

inline std::string name_or(const BuildOptions& o, std::string fallback) { return o.name.empty() ? fallback : o.name; }

// One of the three paper cabinets: a closed carcass of 50 x 30 tubes calibrated to its Table 2 row.
inline Blueprint paper_cabinet(Model& model, PaperItem which, ItemKind kind, std::string name, double spacing,
                               int shelves, const BuildOptions& opts) {
  const auto& row = paper_item(which);
  Blueprint bp;
  bp.name = std::move(name);
  bp.kind = kind;
  bp.size = {row.W, row.D, row.H};
  const Section tube = sections::cabinet_tube();
  Carcass c{row.W, row.D, row.H, opts.panel_spacing.value_or(spacing) * opts.effective_grid_scale(),
            evenly_spaced(shelves), true, find_or_add_section(model, tube)};
  add_carcass(bp.wire, c, 0.5 * tube.contact_width());
  add_cabinet_markers(bp, row.W, row.D, row.H);
  bp.mass = opts.mass_kg.value_or(row.mass);
  bp.cog = cog_target(row.D, opts.cog_h.value_or(row.h), opts.cog_d1.value_or(row.d1));
  bp.contact = ItemContact::paper(which);
  return bp;
}

}  // namespace detail

// Tall cabinet (W900 D400 H1850): double-door steel cabinet with four shelves.
inline ItemInfo build_tall_cabinet(Model& model, const Placement& placement = {}, const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "tall_cabinet");
  detail::check_options(opts, "tall_cabinet '" + name + "'");
  const auto bp = detail::paper_cabinet(model, PaperItem::tall_cabinet, ItemKind::tall_cabinet, name,
                                        detail::tall_cabinet_spacing, 4, opts);
  return detail::realize(model, bp, placement, opts);
}

// Separated cabinets: the upper cabinet (W900 D400 H730, one shelf) stands on the lower one (W900 D400
// H1120, one shelf); two bodies, in contact through the lower top board and the upper bottom board.
struct CabinetPair {
  ItemInfo lower, upper;
};

inline CabinetPair build_separated_cabinets(Model& model, const Placement& placement = {}, const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "separated_cabinets");
  detail::check_options(opts, "separated_cabinets '" + name + "'");
  if (opts.mass_kg || opts.cog_h || opts.cog_d1)
    throw ModelError("separated_cabinets '" + name +
                     "': mass_kg, cog_h and cog_d1 are ambiguous for two bodies; build each cabinet from Table 2");
  CabinetPair pair;
  const auto lower = detail::paper_cabinet(model, PaperItem::lower_separated_cabinet, ItemKind::separated_cabinets,
                                           name + "/lower", detail::lower_cabinet_spacing, 1, opts);
  pair.lower = detail::realize(model, lower, placement, opts);
  Placement on_top = placement;
  on_top.z += paper_item(PaperItem::lower_separated_cabinet).H;
  const auto upper = detail::paper_cabinet(model, PaperItem::upper_separated_cabinet, ItemKind::separated_cabinets,
                                           name + "/upper", detail::upper_cabinet_spacing, 1, opts);
  pair.upper = detail::realize(model, upper, on_top, opts);
  return pair;
}

// Side table (W550 D340 H617) on four casters. Our reading of Table 1 (the paper's Figure 6 is not
// available): four corner columns, the front pair 170 x 40 and the rear pair type 2, stand on casters
// and are joined by a base frame; the top board, a shelf and a back panel are grids of the 445 x 40
// "beams". Wide sections have wide contact distances (half the member width), so the shelf sits above
// 0.25 m and the columns start at 0.10 m.
inline ItemInfo build_side_table(Model& model, const Placement& placement = {}, const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "side_table");
  detail::check_options(opts, "side_table '" + name + "'");
  const auto& row = paper_item(PaperItem::side_table);
  detail::Blueprint bp;
  bp.name = name;
  bp.kind = ItemKind::side_table;
  bp.size = {row.W, row.D, row.H};
  const int front = detail::find_or_add_section(model, sections::side_table_front_column());
  const int rear = detail::find_or_add_section(model, sections::side_table_rear_column());
  const int beam = detail::find_or_add_section(model, sections::side_table_beam());
  const int wheel = detail::find_or_add_section(model, sections::caster());
  const double t = 0.020;  // half the 40 mm thickness of columns and boards: the outer faces are W, D, H
  const double x1 = 0.5 * row.W - t, y1 = 0.5 * row.D - t, z_top = row.H - t;
  const double z_wheel = 0.5 * sections::caster().contact_width(), z_column = 0.10, z_shelf = 0.28;
  const double spacing = opts.panel_spacing.value_or(detail::side_table_spacing) * opts.effective_grid_scale();
  const auto xs = detail::lattice(-x1, x1, spacing, 2);
  const auto ys = detail::lattice(-y1, y1, spacing);
  bp.wire.panel("top", 2, z_top, xs, ys, beam);
  bp.wire.panel("shelf", 2, z_shelf, xs, ys, beam);
  // Base frame joining the column feet above the casters (column section: its 85 mm contact distance
  // stays clear of the floor at 0.10 m). It carries the low part of the mass (h = 308 mm of 617).
  bp.wire.panel("base", 2, z_column, {-x1, x1}, {-y1, y1}, front);
  // Back panel between shelf and top: the measured centre of gravity lies 48 mm behind the middle.
  bp.wire.panel("back", 1, y1, xs, {z_shelf, 0.5 * (z_shelf + z_top), z_top}, beam);
  const std::array<std::pair<const char*, Vec3>, 4> corners{{{"front_left", Vec3(-x1, -y1, 0)},
                                                             {"front_right", Vec3(x1, -y1, 0)},
                                                             {"rear_left", Vec3(-x1, y1, 0)},
                                                             {"rear_right", Vec3(x1, y1, 0)}}};
  for (const auto& [corner, p] : corners) {
    const bool is_front = p.y() < 0;
    const std::string c(corner);
    // The columns' 170 mm side runs along the depth: they are the front and rear strips of the sides.
    bp.wire.add_line("column_" + c, Vec3(p.x(), p.y(), z_column), Vec3(p.x(), p.y(), z_top), is_front ? front : rear,
                     Vec3::UnitY());
    bp.wire.add_line("caster_" + c, Vec3(p.x(), p.y(), z_wheel), Vec3(p.x(), p.y(), z_column), wheel);
    bp.caster_lines.push_back("caster_" + c);
  }
  bp.marker_points = {{"top_centre", Vec3(0, 0, row.H)}, {"top_front_centre", Vec3(0, -0.5 * row.D, row.H)}};
  bp.mass = opts.mass_kg.value_or(row.mass);
  bp.cog = detail::cog_target(row.D, opts.cog_h.value_or(row.h), opts.cog_d1.value_or(row.d1));
  bp.contact = ItemContact::paper(PaperItem::side_table);
  return detail::realize(model, bp, placement, opts);
}

// Desk (W1200 D700 H700): top board grid, two full-depth side panels standing on the floor (their
// bottom edges are the feet) and a modesty panel at the back from 0.3 m up; 50 x 30 tubes throughout.
// The top board is meshed more finely than the sides: it is where falling items land.
inline ItemInfo build_desk(Model& model, const Placement& placement = {}, const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "desk");
  detail::check_options(opts, "desk '" + name + "'");
  const auto& row = paper_item(PaperItem::desk);
  detail::Blueprint bp;
  bp.name = name;
  bp.kind = ItemKind::desk;
  bp.size = {row.W, row.D, row.H};
  const Section tube = sections::cabinet_tube();
  const int s = detail::find_or_add_section(model, tube);
  const double c = 0.5 * tube.contact_width();
  const double x1 = 0.5 * row.W - c, y1 = 0.5 * row.D - c, z0 = c, z1 = row.H - c;
  const double spacing = opts.panel_spacing.value_or(detail::desk_top_spacing) * opts.effective_grid_scale();
  const auto xs = detail::lattice(-x1, x1, spacing, 2);
  const auto ys = detail::lattice(-y1, y1, spacing, 2);
  // Side and modesty panels use every second top-board line, so their lines end on top-board nodes.
  const auto ys_side = detail::every(ys, 2);
  const auto xs_back = detail::every(xs, 2);
  const auto zs_side = detail::lattice(z0, z1, 2 * spacing);
  bp.wire.panel("top", 2, z1, xs, ys, s);
  bp.wire.panel("left", 0, -x1, ys_side, zs_side, s);
  bp.wire.panel("right", 0, x1, ys_side, zs_side, s);
  std::vector<double> zs_back;
  for (double z : zs_side)
    if (z >= 0.3 - 1e-9) zs_back.push_back(z);
  if (zs_back.size() < 2) zs_back = {zs_side[zs_side.size() - 2], zs_side.back()};
  bp.wire.panel("modesty", 1, y1, xs_back, zs_back, s);
  // Centre drawer hanging under the top board: front, bottom grid and back, one grid spacing deep,
  // spanning the middle two thirds of the width and all but the last grid interval of the depth.
  // It is also what puts the desk's centre of gravity high (h = 600 mm of 700).
  const size_t margin = xs.size() / 6;
  const std::vector<double> xs_drawer(xs.begin() + static_cast<long>(margin), xs.end() - static_cast<long>(margin));
  const std::vector<double> ys_drawer(ys.begin(), ys.end() - 1);
  const double z_drawer = z1 - (zs_side[1] - zs_side[0]) / 2;
  bp.wire.panel("drawer_bottom", 2, z_drawer, detail::every(xs_drawer, 2), ys_drawer, s);
  bp.wire.panel("drawer_front", 1, -y1, xs_drawer, {z_drawer, z1}, s);
  bp.wire.panel("drawer_back", 1, ys_drawer.back(), xs_drawer, {z_drawer, z1}, s);
  bp.marker_points = {{"top_front_centre", Vec3(0, -0.5 * row.D, row.H)},
                      {"top_back_centre", Vec3(0, 0.5 * row.D, row.H)},
                      {"top_centre", Vec3(0, 0, row.H)},
                      {"top_front_corner", Vec3(-0.5 * row.W, -0.5 * row.D, row.H)}};
  bp.mass = opts.mass_kg.value_or(row.mass);
  bp.cog = detail::cog_target(row.D, opts.cog_h.value_or(row.h), opts.cog_d1.value_or(row.d1));
  bp.contact = ItemContact::paper(PaperItem::desk);
  return detail::realize(model, bp, placement, opts);
}

// Office chair (W520 D520 H810): five-arm base (type 3) on five casters, gas-lift column (type 3),
// seat (400 x 80, a cross) and backrest (300 x 80: a reclined post and two cross bars). One arm points
// backwards, under the backrest, as on most chairs; the seat reaches further forward than back from the
// column. Table 2 says "steel and plastic": the base, casters and backrest start the calibration at
// plastic's line mass (1200 kg/m^3 instead of 7850), the column and the seat (frame and mechanism) at
// steel's; the calibration then matches 6.2 kg and h = 423 mm with mild density factors.
inline ItemInfo build_office_chair(Model& model, const Placement& placement = {}, const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "office_chair");
  detail::check_options(opts, "office_chair '" + name + "'");
  const auto& row = paper_item(PaperItem::office_chair);
  detail::Blueprint bp;
  bp.name = name;
  bp.kind = ItemKind::office_chair;
  bp.size = {row.W, row.D, row.H};
  const int base = detail::find_or_add_section(model, sections::chair_base());
  const int seat = detail::find_or_add_section(model, sections::chair_seat());
  const int back = detail::find_or_add_section(model, sections::chair_backrest());
  const int wheel = detail::find_or_add_section(model, sections::caster());
  const double plastic = 1200.0 / Material::steel().rho;
  const double z_wheel = 0.5 * sections::caster().contact_width();
  const double r_caster = 0.5 * row.W - z_wheel;  // wheel rim at the footprint's edge
  const double z_arm_tip = 0.09, z_hub = 0.11, z_seat = 0.42, z_back_top = row.H - 0.04;
  const Vec3 hub(0, 0, z_hub);
  for (int k = 0; k < 5; ++k) {
    const double th = std::numbers::pi / 2 + 2 * std::numbers::pi * k / 5;
    const Vec3 wheel_point(r_caster * std::cos(th), r_caster * std::sin(th), z_wheel);
    const Vec3 tip(wheel_point.x(), wheel_point.y(), z_arm_tip);
    bp.wire.add_line("caster_" + std::to_string(k), wheel_point, tip, wheel, Vec3::Zero(), plastic);
    bp.wire.add_line("arm_" + std::to_string(k), tip, hub, base, Vec3::Zero(), plastic);
    bp.caster_lines.push_back("caster_" + std::to_string(k));
  }
  bp.wire.add_line("column", hub, Vec3(0, 0, z_seat), base);
  // Seat: a cross of two 400 mm wide beams through the column head. A wide beam stands for the plate
  // across its width, so no perimeter bars are needed (they would push the contact envelope, half
  // the member width around each bar, far outside the seat).
  const double seat_front = -0.24, seat_rear = 0.16, seat_half_width = 0.20;
  bp.wire.add_line("seat/x", Vec3(-seat_half_width, 0, z_seat), Vec3(seat_half_width, 0, z_seat), seat, Vec3::UnitY());
  bp.wire.add_line("seat/y", Vec3(0, seat_front, z_seat), Vec3(0, seat_rear, z_seat), seat, Vec3::UnitX());
  // Backrest post from the seat's rear end, reclined by 35 mm at the top, with two cross bars.
  const Vec3 post_a(0, seat_rear, z_seat), post_b(0, seat_rear + 0.035, z_back_top);
  bp.wire.add_line("backrest/post", post_a, post_b, back, Vec3::UnitX(), plastic);
  for (double fraction : {0.55, 1.0}) {
    const Vec3 centre = post_a + fraction * (post_b - post_a);
    const std::string bar = fraction < 1 ? "backrest/lower_bar" : "backrest/top_bar";
    bp.wire.add_line(bar, centre - Vec3(0.15, 0, 0), centre + Vec3(0.15, 0, 0), back, Vec3::UnitZ(), plastic);
  }
  bp.marker_points = {{"seat_centre", Vec3(0, 0, z_seat)}, {"backrest_top", post_b}, {"base_centre", hub}};
  bp.mass = opts.mass_kg.value_or(row.mass);
  bp.cog = detail::cog_target(row.D, opts.cog_h.value_or(row.h), opts.cog_d1.value_or(row.d1));
  bp.contact = ItemContact::paper(PaperItem::office_chair);
  return detail::realize(model, bp, placement, opts);
}

namespace detail {
inline Blueprint generic_carcass(Model& model, ItemKind kind, const std::string& name, double W, double D, double H,
                                 std::vector<double> shelf_fractions, bool closed_front, const BuildOptions& opts) {
  check_options(opts, to_string(kind) + " '" + name + "'");
  check_size(W, D, H, to_string(kind) + " '" + name + "'");
  Blueprint bp;
  bp.name = name;
  bp.kind = kind;
  bp.size = {W, D, H};
  const Section tube = sections::cabinet_tube();
  Carcass c{W, D, H, opts.panel_spacing.value_or(generic_spacing) * opts.effective_grid_scale(),
            std::move(shelf_fractions), closed_front, find_or_add_section(model, tube)};
  add_carcass(bp.wire, c, 0.5 * tube.contact_width());
  add_cabinet_markers(bp, W, D, H);
  bp.mass = opts.mass_kg.value_or(sheet_areal_mass * carcass_panel_area(c));
  if (opts.cog_h || opts.cog_d1) bp.cog = cog_target(D, opts.cog_h.value_or(0.5 * H), opts.cog_d1.value_or(0.5 * D));
  const int long_axis = W >= D ? 0 : 1;
  const double mu_a = opts.mu_static_long.value_or(paper_item(PaperItem::tall_cabinet).mu_static_long);
  const double mu_b = opts.mu_static_short.value_or(paper_item(PaperItem::tall_cabinet).mu_static_short);
  bp.contact = ItemContact::from_rule(bp.mass, mu_a, mu_b, long_axis);
  return bp;
}
}  // namespace detail

// Open bookshelf: carcass without doors and `shelves` evenly spaced shelves.
inline ItemInfo build_bookshelf(Model& model, const Placement& placement, double W, double D, double H, int shelves,
                                const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "bookshelf");
  if (shelves < 0 || shelves > 50)
    throw ModelError("bookshelf '" + name + "': shelves must lie in [0, 50] (got " + std::to_string(shelves) + ")");
  const BuildOptions o = detail::with_full_mesh_cog(opts, D, [&](Model& m, const BuildOptions& full) {
    return build_bookshelf(m, {}, W, D, H, shelves, full);
  });
  const auto bp =
      detail::generic_carcass(model, ItemKind::bookshelf, name, W, D, H, detail::evenly_spaced(shelves), false, o);
  return detail::realize(model, bp, placement, o);
}

// Steel locker: closed carcass (a door grid) with a hat shelf at 5/6 of the inner height.
inline ItemInfo build_locker(Model& model, const Placement& placement, double W, double D, double H,
                             const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "locker");
  const BuildOptions o = detail::with_full_mesh_cog(
      opts, D, [&](Model& m, const BuildOptions& full) { return build_locker(m, {}, W, D, H, full); });
  const auto bp = detail::generic_carcass(model, ItemKind::locker, name, W, D, H, {5.0 / 6.0}, true, o);
  return detail::realize(model, bp, placement, o);
}

// Table: top board grid on four corner legs (50 x 30 tubes); the top board's edges are the apron.
inline ItemInfo build_table(Model& model, const Placement& placement, double W, double D, double H,
                            const BuildOptions& opts = {}) {
  const std::string name = detail::name_or(opts, "table");
  detail::check_options(opts, "table '" + name + "'");
  detail::check_size(W, D, H, "table '" + name + "'");
  const BuildOptions o = detail::with_full_mesh_cog(
      opts, D, [&](Model& m, const BuildOptions& full) { return build_table(m, {}, W, D, H, full); });
  detail::Blueprint bp;
  bp.name = name;
  bp.kind = ItemKind::table;
  bp.size = {W, D, H};
  const Section tube = sections::cabinet_tube();
  const int s = detail::find_or_add_section(model, tube);
  const double c = 0.5 * tube.contact_width();
  const double x1 = 0.5 * W - c, y1 = 0.5 * D - c, z0 = c, z1 = H - c;
  const double spacing = o.panel_spacing.value_or(detail::generic_spacing) * o.effective_grid_scale();
  bp.wire.panel("top", 2, z1, detail::lattice(-x1, x1, spacing, 2), detail::lattice(-y1, y1, spacing, 2), s);
  for (auto [leg, x, y] : {std::tuple{"leg_front_left", -x1, -y1}, std::tuple{"leg_front_right", x1, -y1},
                           std::tuple{"leg_rear_left", -x1, y1}, std::tuple{"leg_rear_right", x1, y1}})
    bp.wire.add_line(leg, Vec3(x, y, z0), Vec3(x, y, z1), s);
  bp.marker_points = {{"top_front_centre", Vec3(0, -0.5 * D, H)}, {"top_centre", Vec3(0, 0, H)},
                      {"top_front_corner", Vec3(-0.5 * W, -0.5 * D, H)}};
  const double leg_line_mass = Material::steel().rho * tube.A;
  bp.mass = o.mass_kg.value_or(detail::table_top_areal_mass * W * D + 4 * H * leg_line_mass);
  if (o.cog_h || o.cog_d1)
    bp.cog = detail::cog_target(D, o.cog_h.value_or(0.5 * H), o.cog_d1.value_or(0.5 * D));
  const auto& desk = paper_item(PaperItem::desk);
  bp.contact = ItemContact::from_rule(bp.mass, o.mu_static_long.value_or(desk.mu_static_long),
                                      o.mu_static_short.value_or(desk.mu_static_short), W >= D ? 0 : 1);
  return detail::realize(model, bp, placement, o);
}

}  // namespace furniture_fem
