#pragma once
// furniture_fem/scene/validation.hpp: validate(), what reading a scene alone cannot check, before a run.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "../core/errors.hpp"
#include "../core/model.hpp"
#include "../core/step_length.hpp"
#include "../excitation/known_records.hpp"
#include "../furniture/named_points.hpp"
#include "build.hpp"
#include "item_parameters.hpp"
#include "spec.hpp"

#define FURNITURE_FEM_SCENE_INTERNAL
#include "detail/scene_building.hpp"
#include "detail/scene_occupants.hpp"
#include "detail/scene_exits.hpp"
#include "detail/scene_restraints.hpp"
#include "detail/scene_names.hpp"
#undef FURNITURE_FEM_SCENE_INTERNAL

namespace furniture_fem {

namespace detail {

// Footprint of an item on the table: centre, unit axes along its width and depth, half extents.
struct Footprint {
  Eigen::Vector2d centre, u, v;
  double half_w = 0, half_d = 0;
  std::array<Eigen::Vector2d, 4> corners() const {
    return {centre - half_w * u - half_d * v, centre + half_w * u - half_d * v, centre + half_w * u + half_d * v,
            centre - half_w * u + half_d * v};
  }
};

inline Footprint footprint(const ItemSpec& item) {
  const double yaw = item.yaw_deg * std::numbers::pi / 180.0;
  const Vec3 size = item_size(item);
  return {Eigen::Vector2d(item.x, item.y), Eigen::Vector2d(std::cos(yaw), std::sin(yaw)),
          Eigen::Vector2d(-std::sin(yaw), std::cos(yaw)), 0.5 * size.x(), 0.5 * size.y()};
}

// Depth of overlap of two footprints (separating axes); <= 0 when they are apart or only touch.
inline double overlap_depth(const Footprint& a, const Footprint& b) {
  double depth = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& axis : {a.u, a.v, b.u, b.v}) {
    const double ra = a.half_w * std::abs(a.u.dot(axis)) + a.half_d * std::abs(a.v.dot(axis));
    const double rb = b.half_w * std::abs(b.u.dot(axis)) + b.half_d * std::abs(b.v.dot(axis));
    depth = std::min(depth, ra + rb - std::abs((b.centre - a.centre).dot(axis)));
  }
  return depth;
}

// The items placed so far, in square cells of the table as wide as the largest footprint's box, so
// that an item is compared with its neighbours only: comparing every pair took minutes for 90 000
// items (issue 13). The first overlap reported is the same as the pairwise loop's (lowest index).
class FootprintGrid {
 public:
  explicit FootprintGrid(double cell) : cell_(std::max(cell, 1e-3)) {}
  // The lowest index k of a placed footprint that overlaps fp by more than 1 um (and the depth), or -1.
  std::pair<long, double> first_overlap(const Footprint& fp) const {
    std::pair<long, double> first{-1, 0.0};
    visit(fp, [&](std::vector<Entry>& cell) {
      for (const Entry& e : cell) {
        if (first.first >= 0 && e.index > first.first) continue;
        const double depth = overlap_depth(e.fp, fp);
        if (depth > 1e-6) first = {e.index, depth};
      }
    });
    return first;
  }
  void place(long index, const Footprint& fp) {
    visit(fp, [&](std::vector<Entry>& cell) { cell.push_back({index, fp}); });
  }

 private:
  struct Entry {
    long index;
    Footprint fp;
  };
  template <class F>
  void visit(const Footprint& fp, F&& f) const {
    Eigen::Vector2d lo = fp.centre, hi = fp.centre;
    for (const auto& c : fp.corners()) lo = lo.cwiseMin(c), hi = hi.cwiseMax(c);
    // Validated items lie on the table: the clamp only keeps a bad coordinate's cell in range.
    const auto cell_of = [&](double x) { return static_cast<long>(std::clamp(std::floor(x / cell_), -1e6, 1e6)); };
    for (long i = cell_of(lo.x()); i <= cell_of(hi.x()); ++i)
      for (long j = cell_of(lo.y()); j <= cell_of(hi.y()); ++j) f(cells_[{i, j}]);
  }
  double cell_;
  mutable std::map<std::pair<long, long>, std::vector<Entry>> cells_;
};

// Names end up in CSV headers, file names and console lines: printable, at most 100 bytes. A newline
// in a marker name was written into markers.csv, which the project's own reader then could not read
// back; a 300-character name failed the PNG write after the whole run (issue 13). The problem, or "".
inline constexpr std::size_t max_name_bytes = 100;
inline std::string name_problem(const std::string& name) {
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return "must not hold control characters (a newline, a tab, a NUL...)";
  if (name.size() > max_name_bytes)
    return "must have at most " + std::to_string(max_name_bytes) + " bytes (got " + std::to_string(name.size()) + ")";
  return {};
}
// A path with a control character: a NUL cut the path short where the system read it, so the run
// used another file or folder than the scene names (issue 13).
inline bool has_control_character(const std::string& path) {
  return std::any_of(path.begin(), path.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}
// is_regular_file without the exception: a name longer than the system allows threw a bare
// filesystem_error that named neither the scene nor the key (issue 13); it is "not found".
inline bool is_file(const std::string& path) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

}  // namespace detail

// Whether an item's floor and wall contact is inside the implicit step: contact.implicit `all`, or
// `rigid` and the item rigid (docs/scene/scene_file.md).
inline bool item_contact_inside_step(const SceneSpec& s, const ItemInfo& item) {
  const ImplicitContact implicit = implicit_contact(s.contact);
  return implicit == ImplicitContact::all || (implicit == ImplicitContact::rigid && item_is_rigid(s, item));
}

namespace detail {
// A joint between items is an item pair of the implicit step (docs/restraints/restraints.md, "Between
// items"): both items inside the step and of one kind, both rigid or both finite-element. Held as a load
// through the step instead, a bracket's stiffness on a frame's node is unstable at the usual steps (a
// full cabinet joined to a rigid stack at dt 1 ms sheared its bracket off in 50 ms).
inline std::string joint_problem(const SceneSpec& s, const ItemInfo& a, const ItemInfo& b) {
  const auto said = [&](const ItemInfo& it) {
    return "\"" + it.name + "\" (" + (item_is_rigid(s, it) ? "rigid" : "finite-element") +
           (item_contact_inside_step(s, it) ? "" : ", its contact outside the implicit step") + ")";
  };
  if (item_contact_inside_step(s, a) && item_contact_inside_step(s, b) && item_is_rigid(s, a) == item_is_rigid(s, b)) return {};
  return "joins " + said(a) + " to " + said(b) +
         ": a joint between items needs both inside the implicit step and both rigid or both finite-element "
         "(contact.implicit \"all\" puts every item's contact inside it, \"rigid\" only the rigid items')";
}
}  // namespace detail

// Checks what parsing alone cannot: item names, items inside the table, clear of the walls and of
// each other; record and mesh files present; markers and sectional-force elements that exist on the
// built items; and that every item can be built (mass and centre-of-gravity targets reachable).
// Throws InputError naming the key path and the item.
inline void validate(const SceneSpec& s) {
  const auto fail = [&](const std::string& path, const std::string& message) {
    throw InputError(s.source, 0, path, message);
  };
  const auto item_label = [&](size_t i) { return "item '" + s.items[i].name + "'"; };
  if (const std::string why = step_length_problem(s.dt, SceneSpec::min_dt); !why.empty()) fail("dt", why);
  if (!(s.duration > 0) || !std::isfinite(s.duration))
    fail("duration", "must be positive and finite (got " + detail::fmt(s.duration) + ")");
  if (s.dt > s.duration)
    fail("dt", "must not exceed duration (dt = " + detail::fmt(s.dt) + " s, duration = " + detail::fmt(s.duration) + " s)");
  if (s.ground_motion.level < 0) fail("ground_motion.level", "must not be negative (got " + detail::fmt(s.ground_motion.level) + ")");
  if (s.items.empty()) fail("items", "a scene needs at least one item");
  if (s.ceiling && !(s.ceiling->height > 0 && s.ceiling->height <= scene_reach))  // a SceneSpec made in code
    fail("ceiling.height", "must be positive, finite and at most " + detail::fmt(scene_reach) + " m (got " +
                               detail::fmt(s.ceiling->height) + ")");
  if (s.contact.law.index >= contact_law_registry().size())
    fail("contact.law", "unknown contact law; expected one of: " + contact_law_registry().names());
  const SceneLawInfo& law = scene_law(s.contact.law);
  // The overrides given in code: declared by the law, where they may stand, in range (as the reader checks).
  for (auto [where, o] : {std::pair{"floor", &s.contact.floor}, std::pair{"wall", &s.contact.wall},
                          std::pair{"item", &s.contact.item}})
    for (const auto& [key, value] : o->values) {
      const std::string path = std::string("contact.") + where + "." + key;
      if (law.set_by_rule(key))
        fail(path, "not used by the contact law \"" + std::string(law.name) + "\": " + std::string(law.rule_parameters_why));
      const LawParameter* p = law.parameter(key);
      if (!p) fail(path, "not used by the contact law \"" + std::string(law.name) + "\"");
      if (p->floor_only && std::string_view(where) != "floor") fail(path, "only contact.floor takes it");
      if (!p->accepts(value))
        fail(path, "must lie in " + p->range_text() + " (got " + detail::fmt(value) + ", contact law \"" +
                       std::string(law.name) + "\")");
    }

  std::set<std::string> names;
  std::vector<detail::Footprint> footprints;
  for (size_t i = 0; i < s.items.size(); ++i) {
    const std::string path = "items[" + std::to_string(i) + "]";
    const auto& item = s.items[i];
    if (item.name.empty() || item.name.find_first_of("./") != std::string::npos)
      fail(path + ".name", "must be non-empty and hold no '.' or '/' (got \"" + item.name + "\")");
    if (const auto why = detail::name_problem(item.name); !why.empty()) fail(path + ".name", why);
    if (!names.insert(item.name).second) fail(path + ".name", "duplicate item name \"" + item.name + "\"");
    const ItemKindEntry* kind = item_kind_registry().find(item.kind.name());
    if (!kind)
      fail(path + ".kind", "unknown item kind \"" + to_string(item.kind) + "\"; registered kinds: " +
                               item_kind_registry().names());
    for (const auto& [key, value] : item.params.kind_values) {
      const ItemParameter* declared = kind->parameter(key);
      if (!declared) fail(path + ".params." + key, not_a_parameter_message(*kind));
      if (const auto why = declared->violation(value))
        fail(path + ".params." + key, *why + " (got " + detail::fmt(value) + ")");
    }
    for (const auto key : law.unused_item_parameters)  // a value the law sets itself would be read and ignored
      if (common_parameter_given(item.params, key))
        fail(path + ".params." + std::string(key), "not used by contact law \"" + std::string(law.name) + "\" (" +
                                                       std::string(law.unused_item_parameters_why) + ")");
    if (item.params.stiffness_scale && item_is_rigid(s, item))
      fail(path + ".params.stiffness_scale",
           "a rigid item has no frame stiffness to scale (fidelity \"" + to_string(item.fidelity) + "\"" +
               (item.fidelity == Fidelity::automatic ? ", rigid since no sectional force of it is asked for" : "") +
               "); give the item fidelity \"full\" or \"coarse\", or remove the key (got " +
               detail::fmt(*item.params.stiffness_scale) + ")");
    const Vec3 size = item_size(item);
    if (item.params.cog_h && *item.params.cog_h >= size.z())
      fail(path + ".params.cog_h", "must lie below the item's height " + detail::fmt(size.z()) + " m (got " +
                                       detail::fmt(*item.params.cog_h) + ")");
    if (item.params.cog_d1 && *item.params.cog_d1 >= size.y())
      fail(path + ".params.cog_d1", "must lie within the item's depth " + detail::fmt(size.y()) + " m (got " +
                                        detail::fmt(*item.params.cog_d1) + ")");
    const auto fp = detail::footprint(item);
    const double hx = 0.5 * s.table.size_x, hy = 0.5 * s.table.size_y, tol = 1e-9;
    for (const auto& c : fp.corners())
      if (std::abs(c.x()) > hx + tol || std::abs(c.y()) > hy + tol)
        fail(path, item_label(i) + " lies partly outside the " + detail::fmt(s.table.size_x) + " m x " +
                       detail::fmt(s.table.size_y) + " m table: its footprint corner (" + detail::fmt(c.x()) + ", " +
                       detail::fmt(c.y()) + ") m is off the table");
    for (const auto& wall : s.walls) {
      const Eigen::Vector2d n = wall.normal.head<2>().normalized(), p = wall.point.head<2>();
      const Eigen::Vector2d t(-n.y(), n.x());
      for (const auto& c : fp.corners()) {
        const double inside = (c - p).dot(n), along = (c - p).dot(t);
        if (inside < -tol && std::abs(along) <= 0.5 * wall.width + tol)
          fail(path, item_label(i) + " passes through wall '" + wall.name + "' by " + detail::fmt(-inside) + " m");
      }
    }
    footprints.push_back(fp);
  }
  // Then the items against each other (each one's own checks first: a footprint must be sound).
  double widest = 0;  // the footprints' boxes at any yaw
  for (const auto& fp : footprints) widest = std::max(widest, 2 * std::hypot(fp.half_w, fp.half_d));
  detail::FootprintGrid placed(widest);
  for (size_t i = 0; i < footprints.size(); ++i) {
    if (const auto [k, depth] = placed.first_overlap(footprints[i]); k >= 0)
      fail("items[" + std::to_string(i) + "]", item_label(i) + " and " + item_label(size_t(k)) + " (items[" +
                                                   std::to_string(k) + "]) overlap: their footprints intersect by " +
                                                   detail::fmt(depth) + " m");
    placed.place(long(i), footprints[i]);
  }

  if (detail::has_control_character(s.outputs.folder))
    fail("outputs.folder", "must not hold control characters (a NUL, a newline...)");
  const auto& g = s.ground_motion;
  if (g.source == MotionSource::synthetic) {
    // Not applied to the synthetic motion (reading a file refuses the keys; a SceneSpec made in code is
    // checked here against the defaults).
    if (g.lowpass_hz != GroundMotionSpec{}.lowpass_hz)
      fail("ground_motion.lowpass_hz", "not applied to a synthetic motion (it is generated band-limited); only used "
                                       "with source \"file\"");
    if (g.window_start != 0 || g.window_end)
      fail("ground_motion.window", "not applied to a synthetic motion (it runs from t = 0 for ground_motion.duration); "
                                   "only used with source \"file\"");
    if (!(g.synthetic_duration >= 0.02) || !std::isfinite(g.synthetic_duration))
      fail("ground_motion.duration", "must be a finite time of at least two samples (0.02 s; got " +
                                         detail::fmt(g.synthetic_duration) + ")");
  }
  if (g.scale_to) {
    const std::string key = "ground_motion.scale_to." + detail::enum_name(detail::scale_measure_names, g.scale_to->measure);
    if (g.source != MotionSource::file)
      fail("ground_motion.scale_to", "only used with source \"file\" (a synthetic motion has its pga; points are "
                                     "scaled by level)");
    if (!(g.scale_to->value > 0) || !std::isfinite(g.scale_to->value))
      fail(key, "must be a positive finite " + std::string(g.scale_to->measure == ScaleMeasure::pga   ? "acceleration in m/s^2"
                                                            : g.scale_to->measure == ScaleMeasure::pgv ? "velocity in m/s"
                                                                                                       : "JMA intensity") +
                    " (got " + detail::fmt(g.scale_to->value) + ")");
  }
  if (g.source == MotionSource::file) {
    for (auto [key, file] : {std::pair{"x", &g.file_x}, std::pair{"y", &g.file_y}, std::pair{"z", &g.file_z}}) {
      if (file->empty()) {
        // A JMA CSV file holds the three components: files.x alone.
        if (std::string(key) == "x" || (g.dimensions == MotionDimensions::three_d && g.format != RecordFormat::jma_csv))
          fail(std::string("ground_motion.files.") + key, "required (dimensions \"" +
                                                              detail::enum_name(detail::dimension_names, g.dimensions) + "\")");
        continue;
      }
      if (detail::has_control_character(*file))
        fail(std::string("ground_motion.files.") + key, "must not hold control characters (a NUL, a newline...)");
      if (!detail::is_file(s.resolve(*file)))
        fail(std::string("ground_motion.files.") + key, record_not_found(s.resolve(*file)));
    }
  }
  if (g.source == MotionSource::points) {
    if (const auto problem = detail::points_problem(g.points_x, "ground_motion.x")) fail(problem->first, problem->second);
    for (auto [key, pts] : {std::pair{"y", &g.points_y}, std::pair{"z", &g.points_z}})
      if (!pts->empty())
        if (const auto problem = detail::points_problem(*pts, std::string("ground_motion.") + key))
          fail(problem->first, problem->second);
  }
  if (g.building && g.source == MotionSource::points)
    fail("ground_motion.building", "not used with source \"points\" (the points are the table acceleration as given)");
  if (g.building)
    if (const auto problem = detail::building_problem(*g.building))
      fail("ground_motion.building." + problem->first, problem->second);
  if (g.window_end && *g.window_end <= g.window_start)
    fail("ground_motion.window.end", "must be later than window.start (" + detail::fmt(g.window_start) + " s)");
  for (size_t i = 0; i < s.obstacles.size(); ++i) {
    if (detail::has_control_character(s.obstacles[i].file))
      fail("obstacles[" + std::to_string(i) + "].file", "must not hold control characters (a NUL, a newline...)");
    if (!detail::is_file(s.resolve(s.obstacles[i].file)))
      fail("obstacles[" + std::to_string(i) + "].file", "mesh file not found: \"" + s.resolve(s.obstacles[i].file) + "\"");
  }

  // The restraints' own values first: a stopper's height tilts its item as it is built.
  std::set<std::string> restraint_names;  // a restraints.csv column each
  for (size_t k = 0; k < s.restraints.size(); ++k) {
    const auto& r = s.restraints[k];
    const std::string path = "restraints[" + std::to_string(k) + "]";
    if (const auto why = detail::name_problem(r.name); !why.empty()) fail(path + ".name", why);
    if (!restraint_names.insert(r.name).second) fail(path + ".name", "duplicate restraint name \"" + r.name + "\"");
    if (const auto problem = detail::restraint_problem(r, s)) fail(path + "." + problem->first, problem->second);
  }

  // Build every item once: it proves the calibration targets reachable and gives markers and members.
  Model scratch;
  std::map<std::string, ItemInfo> bodies;
  for (size_t i = 0; i < s.items.size(); ++i) {
    try {
      for (auto& info : build_item(s, i, scratch)) bodies.emplace(info.name, std::move(info));
    } catch (const ModelError& e) {
      fail("items[" + std::to_string(i) + "]", item_label(i) + " cannot be built: " + e.what());
    }
  }
  const auto body_names = [&] {
    std::string list;
    for (const auto& [name, info] : bodies) list += (list.empty() ? "" : ", ") + name;
    return list;
  };
  std::map<std::string, size_t> marker_names;  // a name twice gave two columns of the same name
  for (size_t k = 0; k < s.outputs.markers.size(); ++k) {
    const auto& m = s.outputs.markers[k];
    const std::string path = "outputs.markers[" + std::to_string(k) + "]";
    if (const auto why = detail::name_problem(m.name); !why.empty()) fail(path + ".name", why);
    if (const auto [at, fresh] = marker_names.emplace(m.name, k); !fresh)
      fail(path + ".name", "duplicate marker name \"" + m.name + "\" (also outputs.markers[" +
                               std::to_string(at->second) + "])");
    const auto it = bodies.find(m.item);
    if (it == bodies.end())
      fail(path, "marker \"" + m.name + "\" is on no item: \"" + m.item + "\" is not one of: " + body_names());
    if (!m.point && !it->second.marker(m.marker) && !named_point_local(it->second, m.marker)) {
      std::string list;  // its builder's markers, then its box's points (furniture/named_points.hpp)
      for (const auto& name : named_point_names(it->second)) list += (list.empty() ? "" : ", ") + name;
      fail(path, "item \"" + m.item + "\" has no marker \"" + m.marker + "\"; its markers: " + list);
    }
  }
  for (size_t k = 0; k < s.outputs.sectional_forces.size(); ++k) {
    const auto& f = s.outputs.sectional_forces[k];
    const std::string path = "outputs.sectional_forces[" + std::to_string(k) + "]";
    const auto it = bodies.find(f.item);
    if (it == bodies.end()) fail(path + ".item", "\"" + f.item + "\" is not one of: " + body_names());
    const auto spec = std::find_if(s.items.begin(), s.items.end(), [&](const ItemSpec& i) { return i.name == f.item; });
    if (spec != s.items.end() && spec->fidelity == Fidelity::automatic && it->second.fidelity == Fidelity::rigid)
      fail(path + ".item", "item \"" + f.item + "\" is rigid only (kind \"" + to_string(spec->kind) +
                               "\"): fidelity \"auto\" cannot model it flexible for its sectional forces");
    const int member = find_member(scratch, it->second.body, f.member);
    if (member < 0) fail(path + ".member", "item \"" + f.item + "\" has no member \"" + f.member + "\"");
    if (f.element >= scratch.member(member).element_count)
      fail(path + ".element", "member \"" + f.member + "\" has " + std::to_string(scratch.member(member).element_count) +
                                  " elements (got index " + std::to_string(f.element) + ")");
  }
  std::set<std::string> exit_names;  // an exits.csv column each
  for (size_t k = 0; k < s.exits.size(); ++k) {
    const std::string path = "exits[" + std::to_string(k) + "]";
    if (const auto why = detail::name_problem(s.exits[k].name); !why.empty()) fail(path + ".name", why);
    if (!exit_names.insert(s.exits[k].name).second) fail(path + ".name", "duplicate exit name \"" + s.exits[k].name + "\"");
    if (const auto problem = detail::exit_problem(s.exits[k], s)) fail(path + "." + problem->first, problem->second);
  }
  std::vector<ItemInfo> built;
  for (const auto& [name, info] : bodies) built.push_back(info);
  detail::scene_restraint_set(s, scratch, built, detail::scene_ceiling_z(s));  // each point, anchor and reach
  for (size_t k = 0; k < s.restraints.size(); ++k)
    if (const RestraintSpec& r = s.restraints[k]; !r.anchor_item.empty())
      if (const std::string why = detail::joint_problem(s, bodies.at(r.item), bodies.at(r.anchor_item)); !why.empty())
        fail("restraints[" + std::to_string(k) + "].anchor_item", "restraint '" + r.name + "': " + why);
  std::set<std::string> occupant_names;  // named in strikes and the summary
  for (size_t k = 0; k < s.occupants.size(); ++k) {
    const Occupant& o = s.occupants[k];
    const std::string path = "occupants[" + std::to_string(k) + "]";
    if (const auto why = detail::name_problem(o.name); !why.empty()) fail(path + ".name", why);
    if (!occupant_names.insert(o.name).second) fail(path + ".name", "duplicate occupant name \"" + o.name + "\"");
    if (const auto problem = detail::occupant_problem(o, s)) fail(path + "." + problem->first, problem->second);
    // A person standing inside an item at the start would be struck by it at t = 0, unseen.
    for (const ItemInfo& item : built)
      for (OccupantZone z : {OccupantZone::head, OccupantZone::body})
        if (zone_intrusion(o, z, placed_box(item)) > 0)
          fail(path + ".position", "occupant '" + o.name + "': the " + std::string(to_string(z)) + " is inside item '" +
                                       item.name + "' where it stands at the start");
  }
}

}  // namespace furniture_fem
