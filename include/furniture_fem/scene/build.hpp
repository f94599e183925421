#pragma once
// furniture_fem/scene/build.hpp: a scene's items as bodies of a Model, each built by its kind
// (furniture/item_kinds.hpp) with the item's parameters. build_scene() does not validate: call
// validate() (scene/validation.hpp) first.
#include <string>
#include <vector>

#include "../core/model.hpp"
#include "../furniture/furniture.hpp"
#include "../furniture/item_kinds.hpp"
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

// Builds item `index` of the scene into `model`: one ItemInfo per body (the separated cabinets give
// "<name>/lower" then "<name>/upper"), with the item's contact overrides applied.
// Whether a scene models an item as a rigid body: `rigid`, or `auto` when no sectional force of it is asked for.
inline bool item_is_rigid(const SceneSpec& s, const ItemInfo& item) {
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
