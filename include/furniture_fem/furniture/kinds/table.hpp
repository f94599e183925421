#pragma once
// furniture_fem/furniture/kinds/table.hpp: the kind "table" (build_table, furniture/furniture.hpp).
#include "generic_box.hpp"

namespace furniture_fem {

struct TableKind : ItemKindDefaults {
  static constexpr std::string_view name = "table";
  static constexpr std::string_view meaning = "table of any size: a top board grid on four legs";
  static std::vector<ItemParameter> parameters() {
    const auto& desk = paper_item(PaperItem::desk);
    return generic_box_parameters({1.2, 0.75, 0.72}, desk.mu_static_long, desk.mu_static_short);
  }
  static Vec3 size(const ItemValues& v) { return generic_box_size(v); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues& v, const BuildOptions& o) {
    return {build_table(model, at, v["width"], v["depth"], v["height"], with_static_friction(o, v))};
  }
};

}  // namespace furniture_fem
