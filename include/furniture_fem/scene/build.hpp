#pragma once
// furniture_fem/scene/build.hpp: a scene's items as bodies of a Model, each built by its kind
// (furniture/item_kinds.hpp) with the item's parameters. build_scene() does not validate: call
// validate() (scene/validation.hpp) first.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <string>
#include <vector>

#include "../core/errors.hpp"
#include "../core/model.hpp"
#include "../furniture/furniture.hpp"
#include "../furniture/item_kinds.hpp"
#include "../furniture/named_points.hpp"
#include "spec.hpp"

namespace furniture_fem {

// The registered kind of an item (ModelError naming the kind if it is not registered).
inline const ItemKindEntry& item_kind_of(const ItemSpec& item) { return item_kind_registry().at(item.kind); }

// Outer size (W, D, H) of an item as it will be built: Table 2 for the paper's items (the separated
// cabinets stacked: H = 1120 + 730 mm), the kind's parameters (given or default) for the others.
inline Vec3 item_size(const ItemSpec& item) {
  const ItemKindEntry& kind = item_kind_of(item);
  return kind.size(kind.values(item.params.kind_values));
}

namespace detail {

// A stopper's wedge height: the scene's value or the kind's default.
inline double stopper_wedge_height(const RestraintSpec& r) {
  const auto it = r.values.find("wedge_height");
  return it != r.values.end() ? it->second : find_restraint_parameter(RestraintKind::stopper, "wedge_height")->default_value;
}

// The largest lean up to `wanted` (rad) at which no node of the item comes nearer to a wall than its
// contact distance (half its members' contact width), found by bisection: an item standing close to a
// wall leans until its top touches it. A node already that near a wall at the start is not leaning into it.
template <class Turn>
double wall_lean_limit(const SceneSpec& scene, const std::vector<ItemInfo>& bodies, const Model& model, const Vec3& pivot,
                       Turn turn_by, double wanted) {
  std::vector<std::pair<int, double>> nodes;  // a node and its contact distance
  for (const ItemInfo& b : bodies)
    for (int n : model.body(b.body).nodes) nodes.emplace_back(n, std::numeric_limits<double>::infinity());
  for (auto& [n, half] : nodes)
    for (int e : model.body(model.node(n).body).elements)
      if (model.elements()[e].n1 == n || model.elements()[e].n2 == n) half = std::min(half, 0.5 * model.section_of(e).contact_width());
  const auto clear = [&](double a) {
    const Mat3 Q = turn_by(a);
    for (const WallSpec& w : scene.walls) {
      const Vec3 normal = w.normal.normalized(), along = Vec3::UnitZ().cross(normal).normalized();
      for (const auto& [n, half] : nodes) {
        const Vec3 r = pivot + Q * (model.node(n).X - pivot) - w.point;
        if (std::abs(r.dot(along)) > 0.5 * w.width || r.z() > w.height) continue;
        if ((model.node(n).X - w.point).dot(normal) >= half && r.dot(normal) < half) return false;
      }
    }
    return true;
  };
  if (clear(wanted)) return wanted;
  double lo = 0, hi = wanted;
  for (int k = 0; k < 60; ++k) (clear(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// Stoppers under an item's front edge lean it back: the item is turned about its back bottom edge (its
// nodes' line farthest back and lowest) until the front-most stopper's node stands the wedge's height
// higher (docs/restraints/restraints.md, "stopper"), or less where a wall stops its top
// (wall_lean_limit). Its stoppers must share one height. Nothing is done for an item without stoppers.
inline void lean_on_stoppers(const SceneSpec& scene, std::vector<ItemInfo>& bodies, Model& model) {
  const auto fail = [&](std::size_t k, const std::string& key, const std::string& message) {
    throw InputError(scene.source, 0, "restraints[" + std::to_string(k) + "]." + key,
                     "restraint '" + scene.restraints[k].name + "': " + message);
  };
  const ItemInfo* frame = nullptr;
  std::optional<double> height;
  double lever = 0;  // from the back edge to the front-most stopper's node, in the item frame (m)
  std::size_t first = 0;
  double y_back = -1e300, z_low = 1e300;
  for (std::size_t k = 0; k < scene.restraints.size(); ++k) {
    const RestraintSpec& r = scene.restraints[k];
    const auto on = std::find_if(bodies.begin(), bodies.end(), [&](const ItemInfo& b) { return b.name == r.item; });
    if (r.kind != RestraintKind::stopper || on == bodies.end()) continue;
    const double h = stopper_wedge_height(r);
    if (height && h != *height)
      fail(k, "wedge_height", "an item's stoppers share one height: " + fmt(h) + " m here, " + fmt(*height) + " m in restraints[" +
                                  std::to_string(first) + "]");
    if (!frame) {
      frame = &*on;
      first = k;
      for (const ItemInfo& b : bodies)
        for (int n : model.body(b.body).nodes) {
          const Vec3 local = frame->to_local(model.node(n).X);
          y_back = std::max(y_back, local.y());
          z_low = std::min(z_low, local.z());
        }
    }
    height = h;
    const std::optional<Vec3> point = named_point_local(*on, r.point);
    if (!point) continue;  // placing the restraint names the point's problem
    const Vec3 node = frame->to_local(model.node(nearest_node(model, on->body, on->to_world(*point))).X);
    if (y_back - node.y() < 4 * h)
      fail(k, "point", "a stopper goes under the item's front edge: its node is " + fmt(y_back - node.y()) +
                           " m from the item's back edge, too close to lean the item back by " + fmt(h) + " m");
    lever = std::max(lever, y_back - node.y());
  }
  if (!frame || lever <= 0) return;
  const Vec3 pivot = frame->to_world(Vec3(0, y_back, z_low));
  const auto turn_by = [&](double a) -> Mat3 {
    return frame->R * Eigen::AngleAxisd(-a, Vec3::UnitX()).toRotationMatrix() * frame->R.transpose();
  };
  const double wanted = std::asin(*height / lever);
  const double angle = wall_lean_limit(scene, bodies, model, pivot, turn_by, wanted);
  if (!(angle > 0))
    fail(first, "point", "item \"" + frame->name + "\" stands against a wall: its stoppers cannot lean it back");
  const Mat3 turn = turn_by(angle);
  for (ItemInfo& b : bodies) {
    model.turn_body(b.body, turn, pivot);
    b.R = turn * b.R;
    b.position = pivot + turn * (b.position - pivot);
  }
}

}  // namespace detail

// Builds item `index` of the scene into `model`: one ItemInfo per body (the separated cabinets give
// "<name>/lower" then "<name>/upper"), with the item's contact overrides applied.
// Whether a scene models an item as a rigid body: `rigid`, or `auto` when no sectional force of it is asked for.
// `Item`: the scene's ItemSpec, or an ItemInfo as built (its fidelity and name are the spec's).
template <class Item>
bool item_is_rigid(const SceneSpec& s, const Item& item) {
  if (item.fidelity == Fidelity::rigid) return true;
  if (item.fidelity != Fidelity::automatic) return false;
  for (const auto& r : s.outputs.sectional_forces)
    if (r.item == item.name) return false;
  return true;
}

inline std::vector<ItemInfo> build_item(const SceneSpec& scene, size_t index, Model& model) {
  const ItemSpec& item = scene.items.at(index);
  const ItemParams& p = item.params;
  BuildOptions o;
  o.name = item.name;
  o.fidelity = item.fidelity;
  o.grid_scale = p.grid_scale.value_or(o.grid_scale);
  o.element_length = p.element_length.value_or(o.element_length);
  o.panel_spacing = p.panel_spacing;
  o.mass_kg = p.mass_kg;
  o.cog_h = p.cog_h;
  o.cog_d1 = p.cog_d1;
  o.stiffness_scale = p.stiffness_scale.value_or(o.stiffness_scale);
  const Placement at = Placement::at(item.x, item.y, item.yaw_deg, scene.table.floor_z);
  const ItemKindEntry& kind = item_kind_of(item);
  std::vector<ItemInfo> out = kind.build(model, at, kind.values(p.kind_values), o);
  for (auto& info : out) {
    info.kind = kind.kind;  // a kind may reuse another's builder (a refrigerator built as a locker)
    auto& c = info.contact;
    if (p.alpha_kgf) c.alpha = *p.alpha_kgf * newtons_per_kgf;
    if (p.dc_kgf) c.Dc = *p.dc_kgf * newtons_per_kgf;
    if (p.mu_floor_long) c.mu_floor_long = *p.mu_floor_long;
    if (p.mu_floor_short) c.mu_floor_short = *p.mu_floor_short;
    if (p.mu_wall) c.mu_wall = *p.mu_wall;
    if (p.mu_item) c.mu_item = *p.mu_item;
    if (p.alpha_scale) c.alpha *= *p.alpha_scale;
    if (const double f = p.friction_scale.value_or(1.0); f != 1.0)
      for (double* mu : {&c.mu_floor_long, &c.mu_floor_short, &c.mu_wall, &c.mu_item}) *mu *= f;
    if (p.mass_scale) {
      model.scale_body_mass(info.body, *p.mass_scale);
      info.calibration.mass *= *p.mass_scale;
      info.calibration.target_mass *= *p.mass_scale;
    }
  }
  detail::lean_on_stoppers(scene, out, model);
  return out;
}

// All items of the scene as bodies of one Model, in the order of the scene's items.
inline std::vector<ItemInfo> build_scene(const SceneSpec& scene, Model& model) {
  std::vector<ItemInfo> infos;
  for (size_t i = 0; i < scene.items.size(); ++i)
    for (auto& info : build_item(scene, i, model)) infos.push_back(std::move(info));
  return infos;
}

}  // namespace furniture_fem
