#pragma once
// Internal: the scene's "restraints" (RestraintSpec) read, written, checked and placed: each device's node
// on its item and its anchor in the room (restraints/restraint.hpp, docs/restraints/restraints.md). Shared
// by the reader, the writer, validate() and SceneSimulation. Users include furniture_fem/scene/scene.hpp.
#ifndef FURNITURE_FEM_SCENE_INTERNAL
#error "furniture_fem/scene/detail/scene_restraints.hpp is internal: include <furniture_fem/scene/scene.hpp>"
#endif
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "../../core/errors.hpp"
#include "../../furniture/named_points.hpp"
#include "../../restraints/restraint_set.hpp"
#include "../json_reader.hpp"
#include "../spec.hpp"

namespace furniture_fem::detail {

// How far each kind may reach from its item's point to its anchor (m): a bracket's legs, a strap's
// length, a mat's thickness under a base node (half a member's width and the gel), a pole's extent.
inline constexpr double bracket_reach = 0.15, strap_reach = 1.0, mat_reach = 0.05, pole_min = 0.05, pole_max = 1.5;
// A named point farther than this from every node of its item is not on the item (a chair's box corner).
inline constexpr double restraint_point_tolerance = 0.1;

// The ceiling's height (z, the table's frame), or none without one.
inline std::optional<double> scene_ceiling_z(const SceneSpec& s) {
  if (!s.ceiling) return std::nullopt;
  return s.table.floor_z + s.ceiling->height;
}

inline bool restraint_on_wall(RestraintKind k) { return k == RestraintKind::l_bracket || k == RestraintKind::strap; }

inline std::string restraint_kind_names() {
  std::string names;
  for (RestraintKind k : all_restraint_kinds) names += (names.empty() ? "" : ", ") + std::string(to_string(k));
  return names;
}

// The first problem of a restraint that needs no built model, as (key, message), or none: the reader
// and validate() give SceneSpecs made in code the same checks.
inline std::optional<std::pair<std::string, std::string>> restraint_problem(const RestraintSpec& r, const SceneSpec& s) {
  using P = std::pair<std::string, std::string>;
  if (r.item.empty()) return P{"item", "required: the name of the item it fastens"};
  if (r.point.empty()) return P{"point", "required: a named point of the item (e.g. \"top_back_left\")"};
  if (restraint_on_wall(r.kind) && !r.anchor_item.empty()) {  // joining two items
    if (!r.wall.empty() || r.height) return P{"anchor_item", "a restraint is fixed to a wall or to another item, not both"};
    if (r.anchor_point.empty()) return P{"anchor_point", "required with anchor_item: a named point of that item"};
    if (r.anchor_item == r.item) return P{"anchor_item", "must name another item than \"" + r.item + "\""};
  } else if (restraint_on_wall(r.kind)) {
    if (!r.anchor_point.empty()) return P{"anchor_point", "given without anchor_item"};
    if (r.wall.empty()) return P{"wall", "required for a " + std::string(to_string(r.kind)) + ": the wall (or anchor_item) it is fixed to"};
    if (std::none_of(s.walls.begin(), s.walls.end(), [&](const WallSpec& w) { return w.name == r.wall; }))
      return P{"wall", "no wall named \"" + r.wall + "\" in the scene"};
    if (r.height && !(*r.height >= 0 && *r.height <= scene_reach))
      return P{"height", "must be a height above the floor from 0 to " + fmt(scene_reach) + " m (got " + fmt(*r.height) + ")"};
  }
  for (const auto& [key, value] : r.values) {
    const RestraintParameter* d = find_restraint_parameter(r.kind, key);
    if (!d) return P{key, "not a parameter of a " + std::string(to_string(r.kind))};
    if (!d->accepts(value))
      return P{key, "must be in " + d->range_text() + " " + std::string(d->unit) + " (got " + fmt(value) + ")"};
  }
  return std::nullopt;
}

inline RestraintSpec read_restraint(const nlohmann::json& v, const std::string& path, const std::string& source,
                                    std::size_t index) {
  const ObjectReader o(v, path, source);
  RestraintSpec r;
  const auto kind_name = o.optional_string("kind");
  if (!kind_name) o.fail(o.path("kind"), "required: one of " + restraint_kind_names());
  const auto kind = restraint_kind_from_string(*kind_name);
  if (!kind) o.fail(o.path("kind"), "unknown restraint kind \"" + *kind_name + "\"; expected one of: " + restraint_kind_names());
  r.kind = *kind;
  std::vector<std::string_view> allowed = {"name", "kind", "item", "point"};
  if (restraint_on_wall(r.kind)) allowed.insert(allowed.end(), {"wall", "height", "anchor_item", "anchor_point"});
  if (r.kind == RestraintKind::l_bracket) allowed.push_back("screws");
  for (const RestraintParameter& p : restraint_parameters(r.kind)) allowed.push_back(p.key);
  o.allow_only(allowed, "key of a " + std::string(to_string(r.kind)));
  r.name = o.string("name", std::string(to_string(r.kind)) + "_" + std::to_string(index + 1));
  r.item = o.string("item", "");
  r.point = o.string("point", "");
  r.wall = o.string("wall", "");
  r.anchor_item = o.string("anchor_item", "");
  r.anchor_point = o.string("anchor_point", "");
  if (o.has("height")) r.height = o.number("height", 0);
  if (o.has("screws")) {
    const std::string base = o.string("screws", "");
    if (base != "stud" && base != "board") o.fail(o.path("screws"), "expected \"stud\" or \"board\", got \"" + base + "\"");
    r.screws = base == "stud" ? ScrewBase::stud : ScrewBase::board;
  }
  for (const RestraintParameter& p : restraint_parameters(r.kind))
    if (o.has(p.key)) r.values[std::string(p.key)] = o.number(p.key, 0);
  return r;
}

inline nlohmann::json restraint_json(const RestraintSpec& r) {
  nlohmann::json j = {{"name", r.name}, {"kind", std::string(to_string(r.kind))}, {"item", r.item}, {"point", r.point}};
  if (!r.anchor_item.empty()) j.update({{"anchor_item", r.anchor_item}, {"anchor_point", r.anchor_point}});
  else if (restraint_on_wall(r.kind)) j["wall"] = r.wall;
  if (r.height) j["height"] = *r.height;
  if (r.kind == RestraintKind::l_bracket) j["screws"] = r.screws == ScrewBase::stud ? "stud" : "board";
  for (const auto& [key, value] : r.values) j[key] = value;
  return j;
}

// The parameters a restraint runs with: its kind's defaults (a bracket's for its screws), then the file's.
inline RestraintParams restraint_params(const RestraintSpec& r) {
  RestraintParams p = default_restraint_params(r.kind);
  if (r.kind == RestraintKind::l_bracket) set_screw_base_defaults(p, r.screws);
  for (const auto& [key, value] : r.values) p.*(find_restraint_parameter(r.kind, key)->field) = value;
  return p;
}

// Restraint i of the scene placed on the built model: its node, rest point, anchor and normal. A problem
// is an InputError naming restraints[i] and the key. `ceiling_z`: the ceiling's height, none without one.
inline Restraint place_restraint(const SceneSpec& s, std::size_t i, const Model& model, const std::vector<ItemInfo>& items,
                                 std::optional<double> ceiling_z) {
  const RestraintSpec& spec = s.restraints[i];
  const auto fail = [&](const std::string& key, const std::string& message) {
    throw InputError(s.source, 0, "restraints[" + std::to_string(i) + "]." + key, "restraint '" + spec.name + "': " + message);
  };
  // A body by name and its node nearest a named point of it, each problem named by its key.
  const auto locate = [&](const char* item_key, const std::string& name, const char* point_key, const std::string& point) {
    const ItemInfo* item = nullptr;
    std::string bodies;
    for (const ItemInfo& it : items) {
      if (it.name == name) item = &it;
      if (it.name.rfind(name + "/", 0) == 0) bodies += (bodies.empty() ? "\"" : ", \"") + it.name + "\"";
    }
    if (!item)
      fail(item_key, bodies.empty() ? "no item named \"" + name + "\"" : "item \"" + name + "\" has several bodies: name one of " + bodies);
    const std::optional<Vec3> local = named_point_local(*item, point);
    if (!local) {
      std::string names;
      for (const auto& n : named_point_names(*item)) names += (names.empty() ? "" : ", ") + n;
      fail(point_key, "item \"" + name + "\" has no point named \"" + point + "\"; its points: " + names);
    }
    const int node = nearest_node(model, item->body, item->to_world(*local));
    const double off = (model.node(node).X - item->to_world(*local)).norm();
    if (off > restraint_point_tolerance)
      fail(point_key, "no node of \"" + name + "\" within " + fmt(restraint_point_tolerance) + " m of its point \"" + point +
                          "\" (the nearest is " + fmt(off) + " m away)");
    return std::pair(item, node);
  };
  Restraint r;
  r.name = spec.name;
  r.kind = spec.kind;
  const auto [item, node] = locate("item", spec.item, "point", spec.point);
  r.body = item->body;
  r.node = node;
  r.rest = model.node(r.node).X;
  r.p = restraint_params(spec);
  if (!spec.anchor_item.empty()) {  // joining two items: the anchor is the other item's node
    const auto [other, anchor_node] = locate("anchor_item", spec.anchor_item, "anchor_point", spec.anchor_point);
    if (other->body == item->body) fail("anchor_item", "must be another body than the restraint's item");
    r.anchor_body = other->body;
    r.anchor_node = anchor_node;
    r.anchor = model.node(anchor_node).X;
    const double length = (r.rest - r.anchor).norm();
    r.normal = length > 1e-6 ? Vec3((r.rest - r.anchor) / length) : Vec3::UnitZ();
    const double reach = spec.kind == RestraintKind::l_bracket ? bracket_reach : strap_reach;
    if (length > reach)
      fail("anchor_point", "its points are " + fmt(length) + " m apart; a " + std::string(to_string(spec.kind)) + " reaches " + fmt(reach) + " m");
    return r;
  }
  const double floor_z = s.table.floor_z;
  switch (spec.kind) {
    case RestraintKind::l_bracket:
    case RestraintKind::strap: {
      const WallSpec& w = *std::find_if(s.walls.begin(), s.walls.end(), [&](const WallSpec& x) { return x.name == spec.wall; });
      r.normal = w.normal.normalized();
      const double gap = (r.rest - w.point).dot(r.normal);
      const double reach = spec.kind == RestraintKind::l_bracket ? bracket_reach : strap_reach;
      r.anchor = r.rest - gap * r.normal;
      if (spec.height) r.anchor.z() = floor_z + *spec.height;
      const double length = (r.rest - r.anchor).norm();
      if (gap < -1e-9 || length > reach)
        fail("wall", "its point \"" + spec.point + "\" is " + fmt(length) + " m from its anchor on wall \"" + w.name +
                         "\"" + (gap < 0 ? ", behind the wall" : "") + "; a " + std::string(to_string(spec.kind)) +
                         " reaches " + fmt(reach) + " m");
      const Vec3 along = Vec3::UnitZ().cross(r.normal).normalized();
      if (std::abs((r.anchor - w.point).dot(along)) > 0.5 * w.width || r.anchor.z() > floor_z + w.height)
        fail("height", "its anchor lies off wall \"" + w.name + "\" (" + fmt(w.width) + " m wide, " + fmt(w.height) + " m high)");
      break;
    }
    case RestraintKind::mat:
      r.normal = Vec3::UnitZ();
      r.anchor = Vec3(r.rest.x(), r.rest.y(), floor_z);
      if (r.rest.z() - floor_z > mat_reach)
        fail("point", "a mat goes under the item's base: its point \"" + spec.point + "\" is " + fmt(r.rest.z() - floor_z) +
                          " m above the floor (at most " + fmt(mat_reach) + " m)");
      break;
    case RestraintKind::stopper:  // the item already leans back on it (lean_on_stoppers, scene/build.hpp)
      r.normal = Vec3::UnitZ();
      r.anchor = Vec3(r.rest.x(), r.rest.y(), floor_z);
      if (r.rest.z() - floor_z - r.p.wedge_height > mat_reach)
        fail("point", "a stopper goes under the item's front edge: its point \"" + spec.point + "\" is " +
                          fmt(r.rest.z() - floor_z - r.p.wedge_height) + " m above the wedge (at most " + fmt(mat_reach) + " m)");
      break;
    case RestraintKind::pole:
      if (!ceiling_z) fail("kind", "a pole presses against the ceiling: the scene has none (\"ceiling\": {\"height\": ...})");
      r.normal = -Vec3::UnitZ();
      r.anchor = Vec3(r.rest.x(), r.rest.y(), *ceiling_z);
      if (const double gap = *ceiling_z - r.rest.z(); gap < pole_min || gap > pole_max)
        fail("point", "a pole spans " + fmt(pole_min) + " to " + fmt(pole_max) + " m: its point \"" + spec.point +
                          "\" is " + fmt(gap) + " m below the ceiling");
      break;
  }
  return r;
}

inline RestraintSet scene_restraint_set(const SceneSpec& s, const Model& model, const std::vector<ItemInfo>& items,
                                        std::optional<double> ceiling_z) {
  std::vector<Restraint> placed;
  for (std::size_t i = 0; i < s.restraints.size(); ++i) placed.push_back(place_restraint(s, i, model, items, ceiling_z));
  try {
    return RestraintSet(std::move(placed));
  } catch (const ModelError& e) {  // a combination of values the kind refuses (a snapping softening ...)
    throw InputError(s.source, 0, "restraints", e.what());
  }
}

}  // namespace furniture_fem::detail
