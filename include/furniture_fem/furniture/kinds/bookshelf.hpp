#pragma once
// furniture_fem/furniture/kinds/bookshelf.hpp: the kind "bookshelf" (build_bookshelf, furniture/furniture.hpp).
#include "generic_box.hpp"

namespace furniture_fem {

struct BookshelfKind : ItemKindDefaults {
  static constexpr std::string_view name = "bookshelf";
  static constexpr std::string_view meaning = "open steel shelving of any size, evenly spaced shelves";
  static std::vector<ItemParameter> parameters() {
    const auto& tall = paper_item(PaperItem::tall_cabinet);
    auto p = generic_box_parameters({0.9, 0.3, 1.8}, tall.mu_static_long, tall.mu_static_short);
    p.push_back({"shelves", "-", 0, 50, false, 4, "number of shelves, evenly spaced", true});
    return p;
  }
  static Vec3 size(const ItemValues& v) { return generic_box_size(v); }
  static std::vector<ItemInfo> build(Model& model, const Placement& at, const ItemValues& v, const BuildOptions& o) {
    return {build_bookshelf(model, at, v["width"], v["depth"], v["height"], v.integer("shelves"), with_static_friction(o, v))};
  }
};

}  // namespace furniture_fem
